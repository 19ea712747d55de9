// The LCM side of the supervisor: HEARTBEAT and SUPERVISOR_ORDERS in; SUPERVISOR_STATUS
// (1 Hz, and promptly on every change) and, while the robot is held, zero BASE_CMD out.
// Destroying it stops every child (dependents first) and waits for them: children are
// resources of a cleanly exiting supervisor. A killed supervisor leaves them running for
// its successor to adopt.
#pragma once

#include <chrono>
#include <deque>
#include <memory>
#include <utility>

#include "runtime/node.h"
#include "supervisor.h"
#include "supervisor_options.h"

namespace rgnav::supervisor {

class SupervisorNode
{
 public:
  SupervisorNode(runtime::Node& node, std::unique_ptr<Supervisor> supervisor, SupervisorOptions options,
                 SupervisorChannels channels);
  ~SupervisorNode();
  SupervisorNode(const SupervisorNode&) = delete;
  SupervisorNode& operator=(const SupervisorNode&) = delete;

  void publish_status();

 private:
  using Clock = std::chrono::steady_clock;
  void on_tick();
  void publish_hold();
  void drain();

  runtime::Node& node_;
  std::unique_ptr<Supervisor> sup_;
  const SupervisorOptions options_;
  const SupervisorChannels channels_;
  std::deque<std::pair<int64_t, int64_t>> seen_orders_;  // (order_id, utime) of recent orders
  Clock::time_point last_status_{};
  int64_t hold_seq_ = 0;
  std::string hostname_;
};

}  // namespace rgnav::supervisor
