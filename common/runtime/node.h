// The process runtime every rgnav process runs in: one bus, typed and validated
// publish/subscribe, message time, wall-time and message-time timers, a HEARTBEAT at 5 Hz,
// and a loop that ends cleanly on SIGINT/SIGTERM. Handlers and timers run in run()'s thread,
// one at a time, so node adapters need no locks.
//
// Under run() on a real bus the heartbeat is sent by a thread of its own beside the loop: a
// handler busy with long work (a region described again, a loop closure, a global search)
// does not silence it. What shows a stuck loop instead is the heartbeat's progress counter
// (loop turns, plus note_progress() from long work) and busy_ms; the supervisor bounds the
// time without progress per process. SIGSTOP, a crash or a deadlock of the whole process
// still silence the heartbeat. Tests driving spin_once() beat on the loop as before.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "bus/bus.h"
#include "bus/drop_counter.h"
#include "bus/typed.h"
#include "config/config.h"
#include "runtime/proc_stats.h"
#include "runtime/signal_watcher.h"
#include "time/message_time.h"

namespace rgnav::runtime {

struct NodeOptions
{
  std::string name;                          // process name in heartbeats and logs
  std::string lcm_url;                       // "" = LCM_DEFAULT_URL or LCM's default
  std::string heartbeat_channel = "HEARTBEAT";
  double heartbeat_hz = 5.0;
  // Heartbeat state turns DEGRADED when the newest input is older than this (0 = never).
  std::chrono::milliseconds input_stale_after{2000};
  // The message clock takes a stamp this far ahead of it only once a second input confirms it
  // (time::MessageClock); a node whose inputs come at tens of Hz takes a tighter bound.
  std::chrono::milliseconds max_stamp_jump{5000};
  // SCHED_FIFO priority when permitted (0: normal) for the thread that creates the node (the
  // event loop: input, timers, output) and the threads started from then on, LCM's receive
  // thread among them (Node's LCM constructor only). For the drive chain's processes: their
  // real-time threads are no help when a message they need waits in a starved event loop (under
  // load the base driver's ODOMETRY came late and the low-level drive stopped for stale odometry
  // with nothing wrong). A thread that asks for its own priority keeps it.
  int realtime_priority = 0;
};

// Reads the `node:` section every process config has.
NodeOptions load_node_options(const config::Config& node_section, const std::string& default_name);

class Node
{
 public:
  using Clock = std::chrono::steady_clock;

  // Creates an LcmBus from options.lcm_url (after blocking the signals).
  explicit Node(NodeOptions options);
  // Uses the given bus (tests: FakeBus, memq://).
  Node(NodeOptions options, std::unique_ptr<bus::Bus> bus);
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  // Accepted messages advance the message clock (by their utime) and the input age.
  template <class T>
  bus::SubscriptionId subscribe(const std::string& channel, std::function<void(const T&)> handler);
  template <class T>
  bool publish(const std::string& channel, const T& msg) { return bus::publish(*bus_, channel, msg); }

  // Wall-time periodic task (heartbeat, hardware loops, periodic republish). The first call
  // is one period after registration.
  void every(std::chrono::microseconds period, std::function<void()> fn);
  // Message-time periodic task: fn(t) runs when message time crosses each multiple of period.
  void every_message_time(time::Duration period, std::function<void(time::Time)> fn);
  // An extra descriptor to wait on (a serial port): fd() is asked on every loop turn (-1 =
  // nothing to wait on now, e.g. while a device is unplugged); on_ready runs in the loop when
  // it is readable or hung up, so hardware input is handled as soon as it arrives.
  void watch_fd(std::function<int()> fd, std::function<void()> on_ready);

  // Runs until SIGINT/SIGTERM or request_stop(). Returns 0, or 1 after a bus error.
  int run();
  // One loop iteration, waiting at most max_wait (tests). False once a stop was requested.
  bool spin_once(std::chrono::milliseconds max_wait);
  void request_stop() { stop_requested_ = true; }
  bool stop_requested() const { return stop_requested_; }

  // Overrides the automatic heartbeat state (heartbeat_t::STATE_*) with a reason, until
  // clear_status() is called.
  void set_status(int8_t state, const std::string& text);
  void clear_status();
  void publish_heartbeat();
  // Long work calls this between its steps (thread-safe, cheap): the heartbeat's progress
  // counter moves on, so the supervisor sees "busy and progressing", not "hung".
  void note_progress() { progress_.fetch_add(1, std::memory_order_relaxed); }
  int64_t progress() const { return progress_.load(std::memory_order_relaxed); }

  const std::string& name() const { return options_.name; }
  const time::MessageClock& clock() const { return clock_; }
  bus::Bus& bus() { return *bus_; }
  bus::DropCounter& drops() { return drops_; }
  int64_t messages_in() const { return messages_in_; }
  int64_t heartbeat_seq() const { return heartbeat_seq_.load(); }

 private:
  struct WallTimer
  {
    Clock::duration period;
    Clock::time_point next;
    std::function<void()> fn;
  };
  struct MessageTimer
  {
    time::Duration period;
    bool started = false;
    time::Time next{};
    std::function<void(time::Time)> fn;
  };

  void on_input(int64_t utime);
  void run_due_timers();
  Clock::time_point next_deadline() const;
  void heartbeat_loop();
  void send_heartbeat();
  void start_heartbeat_thread();
  void stop_heartbeat_thread();

  NodeOptions options_;
  std::unique_ptr<SignalWatcher> signals_;  // before bus_: threads LCM may start inherit the mask
  std::unique_ptr<bus::Bus> bus_;
  bus::DropCounter drops_;
  time::MessageClock clock_;  // made from options_.max_stamp_jump
  ProcStats stats_;
  std::vector<WallTimer> wall_timers_;
  std::vector<MessageTimer> message_timers_;
  static constexpr size_t kMaxFdWatches = 8;
  struct FdWatch
  {
    std::function<int()> fd;
    std::function<void()> on_ready;
  };
  std::vector<FdWatch> fd_watches_;
  std::string host_;
  std::atomic<bool> stop_requested_{false};
  bool bus_failed_ = false;
  bool has_subscriptions_ = false;
  bool has_input_ = false;
  Clock::time_point last_input_{};
  int64_t messages_in_ = 0;
  std::atomic<int64_t> heartbeat_seq_{0};
  bool status_override_ = false;
  int8_t override_state_ = 0;
  std::string override_text_;
  int64_t dropped_seen_ = 0;    // drops_.total() as of the loop's last turn (state_mutex_)
  // Liveness of the loop, read by the heartbeat thread.
  std::atomic<int64_t> progress_{0};
  std::atomic<int64_t> busy_since_ns_{0};   // steady clock; 0 = waiting in poll
  // The heartbeat beside the loop (run() on a bus whose publish is thread-safe). state_mutex_
  // guards what publish_heartbeat() reads that the loop writes.
  std::mutex state_mutex_;
  std::mutex send_mutex_;   // one heartbeat sender at a time
  std::mutex beat_mutex_;
  std::condition_variable beat_wake_;
  bool beat_stop_ = false;
  std::thread beat_thread_;
  std::atomic<bool> beat_beside_loop_{false};
};

template <class T>
bus::SubscriptionId Node::subscribe(const std::string& channel, std::function<void(const T&)> handler)
{
  has_subscriptions_ = true;
  return bus::subscribe<T>(
      *bus_, channel,
      [this, handler = std::move(handler)](const T& msg, const bus::RawMessage&) {
        on_input(msg.utime);
        handler(msg);
        note_progress();   // one turn of the loop may handle many messages
      },
      &drops_);
}

}  // namespace rgnav::runtime
