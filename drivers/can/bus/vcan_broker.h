// The user-space virtual CAN bus: a broker on a Unix SOCK_SEQPACKET socket that forwards
// every frame a client sends to all *other* clients (like a CAN bus with SocketCAN's default
// loopback, without receiving one's own frames), between threads or processes. It stands in
// for kernel vcan where the kernel has no CAN (see vcan_protocol.h for the wire format).
//
// Test hooks (also reachable from any client through control packets) make the bus misbehave
// on purpose: drop matching frames, inject error frames, put one client bus-off for a while,
// disconnect a client. A client that does not read loses frames (its socket buffer overflows),
// as a real controller's receive FIFO would.
#pragma once

#include <linux/can.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace rgnav::can {

struct VcanBrokerStats
{
  uint64_t frames_in = 0;         // data frames received from clients
  uint64_t deliveries = 0;        // frames handed to a client socket
  uint64_t dropped_by_hook = 0;   // frames removed by drop rules or bus-off
  uint64_t overflow_drops = 0;    // deliveries lost because a client's buffer was full
  uint64_t rejected = 0;          // malformed packets (bad size, bad DLC, error-flag frames)
};

class VcanBroker
{
 public:
  // Binds and listens on `path` ('@name' = abstract namespace). A stale socket file left by a
  // dead broker is replaced; a live broker on the same path is an error. Throws CanError.
  explicit VcanBroker(const std::string& path);
  ~VcanBroker();
  VcanBroker(const VcanBroker&) = delete;
  VcanBroker& operator=(const VcanBroker&) = delete;

  // Serves in the caller's thread: accepts, forwards, runs timers; waits up to `timeout`.
  void run_once(std::chrono::milliseconds timeout);
  // Or serves in a background thread until stop() / destruction. realtime_priority > 0 asks
  // SCHED_FIFO for that thread: the bus stands in for wires, which no load delays, and a
  // starved broker holds back every heartbeat on it at once (the master then takes healthy
  // drives for lost).
  void start(int realtime_priority = 0);
  void stop();

  // --- test hooks (thread-safe) ---
  // Drops the next `count` frames with (id & mask) == (can_id & mask); count < 0: until cleared.
  void drop_frames(canid_t can_id, canid_t mask, int64_t count);
  void clear_drops();
  // Sends an error frame of class `error_class` (CAN_ERR_*) to every client.
  void inject_error(can_err_mask_t error_class, uint8_t controller_detail = 0);
  // Client `name` receives a bus-off error frame, can neither send nor receive for
  // `duration`, then receives CAN_ERR_RESTARTED. False if there is no such client.
  bool bus_off(const std::string& client_name, std::chrono::milliseconds duration);
  // Closes client `name`'s connection. False if there is no such client.
  bool disconnect(const std::string& client_name);

  std::vector<std::string> client_names() const;
  VcanBrokerStats stats() const;
  const std::string& path() const { return path_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Client
  {
    int fd = -1;
    std::string name;
    std::optional<Clock::time_point> bus_off_until;
  };
  struct DropRule
  {
    canid_t id;
    canid_t mask;
    int64_t remaining;  // < 0: forever
  };

  void accept_clients();
  // Reads every packet waiting on client i; false if the client hung up.
  bool read_client(size_t i);
  void forward(size_t from, const can_frame& f);
  void handle_control(size_t from, const void* data);
  void deliver(Client& c, const can_frame& f);
  void expire_bus_off(Clock::time_point now);
  void close_client(size_t i);
  Client* find(const std::string& name);
  bool bus_off_locked(const std::string& name, std::chrono::milliseconds duration);
  bool disconnect_locked(const std::string& name);
  void wake();

  std::string path_;
  bool unlink_on_close_ = false;
  int listen_fd_ = -1;
  int wake_fd_ = -1;
  mutable std::mutex mu_;
  std::vector<Client> clients_;
  std::vector<DropRule> drops_;
  VcanBrokerStats stats_;
  uint64_t next_client_ = 1;
  std::thread thread_;
  std::atomic<bool> stop_{false};
};

}  // namespace rgnav::can
