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

#include "order_auth.h"
#include "runtime/node.h"
#include "supervisor.h"
#include "supervisor_options.h"

namespace rgnav::supervisor {

class SupervisorNode
{
 public:
  // orders: only what it lets through is carried out (signed orders, order_auth.h).
  SupervisorNode(runtime::Node& node, std::unique_ptr<Supervisor> supervisor, SupervisorOptions options,
                 SupervisorChannels channels, OrderGate orders);
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
  OrderGate orders_;
  Clock::time_point last_status_{};
  Clock::time_point last_tick_{};   // the previous on_tick(): its lateness is the host's stall
  int64_t hold_seq_ = 0;
  std::string hostname_;
};

}  // namespace rgnav::supervisor
