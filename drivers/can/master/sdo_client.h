// Asynchronous expedited SDO client (CiA 301 §7.2.4.3): one transfer in flight per server,
// further requests queue behind it. A transfer ends with the server's response, its abort, or
// a local timeout; timeouts are retried `retries` times, aborts never (an abort is the
// server's definitive answer). After the last timeout the client sends the abort "SDO
// protocol timed out" so the server side is clean. Callbacks run inside handle()/tick().
#pragma once

#include <linux/can.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>

namespace rgnav::can::master {

struct SdoResult
{
  bool ok = false;
  uint32_t value = 0;       // uploaded value (uploads)
  uint8_t size = 0;         // bytes indicated by the server (uploads), 0 = not indicated
  uint32_t abort_code = 0;  // server's abort, or sdo::kTimeout / kBadCommand raised here
  bool timed_out = false;
  std::string error;        // human-readable, names node and object
};

struct SdoClientOptions
{
  std::chrono::milliseconds timeout{50};
  int retries = 2;
};

class SdoClient
{
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const can_frame&)>;
  using Callback = std::function<void(const SdoResult&)>;

  SdoClient(SdoClientOptions options, Sink send) : options_(options), send_(std::move(send)) {}

  void upload(uint8_t node, uint16_t index, uint8_t sub, Callback done);
  void download(uint8_t node, uint16_t index, uint8_t sub, uint32_t value, uint8_t size, Callback done);

  // True if `f` was an SDO response from a server with a transfer in flight.
  bool handle(const can_frame& f, Clock::time_point now);
  // Starts queued transfers and times out the ones in flight.
  void tick(Clock::time_point now);
  // Forgets everything queued or in flight for `node` (no callbacks).
  void cancel(uint8_t node);
  bool idle(uint8_t node) const;

 private:
  struct Request
  {
    bool upload = false;
    uint16_t index = 0;
    uint8_t sub = 0;
    uint32_t value = 0;
    uint8_t size = 4;
    Callback done;
  };
  struct Channel
  {
    std::deque<Request> queue;
    bool in_flight = false;
    int attempts = 0;
    Clock::time_point deadline{};
  };
  // Queues `r` behind the node's other transfers; once the client knows the time (ticked), it
  // starts the queue right away rather than at the next tick.
  void enqueue(uint8_t node, Request r);
  void start(uint8_t node, Channel& ch, Clock::time_point now);
  void finish(uint8_t node, SdoResult result);
  can_frame request_frame(uint8_t node, const Request& r) const;

  SdoClientOptions options_;
  Sink send_;
  std::map<uint8_t, Channel> channels_;
  std::optional<Clock::time_point> now_;
};

}  // namespace rgnav::can::master
