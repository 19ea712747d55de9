// Master-side heartbeat consumer (CiA 301 §7.2.8.3.2): the NMT state each node reports, and
// which nodes have been silent for longer than their consumer time. Monitoring of a node
// starts with its first heartbeat (before that it is "not seen", not "lost").
#pragma once

#include <linux/can.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "canopen/protocol.h"

namespace rgnav::can::master {

class HeartbeatMonitor
{
 public:
  using Clock = std::chrono::steady_clock;

  void watch(uint8_t node, std::chrono::milliseconds consumer_time);
  // The reporting node and its state if `f` is a heartbeat (or boot-up) of a watched node.
  std::optional<std::pair<uint8_t, canopen::NmtState>> handle(const can_frame& f, Clock::time_point now);
  // Nodes that became lost at this call (each reported once per loss).
  std::vector<uint8_t> tick(Clock::time_point now);
  bool lost(uint8_t node) const;
  bool seen(uint8_t node) const;
  std::optional<canopen::NmtState> state(uint8_t node) const;
  // Forget every node's history (e.g. after a bus-off): monitoring restarts with the next heartbeat.
  void reset();

 private:
  struct Entry
  {
    std::chrono::milliseconds consumer_time{0};
    bool seen = false;
    bool lost = false;
    Clock::time_point last{};
    canopen::NmtState state = canopen::NmtState::kBootUp;
  };
  std::map<uint8_t, Entry> nodes_;
};

}  // namespace rgnav::can::master
