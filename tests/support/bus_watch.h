// Listening to a live bus from a test: heartbeats of child processes, and typed messages on a
// channel. Single-threaded: the waits pump the bus themselves.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/drop_counter.h"
#include "bus/lcm_bus.h"
#include "rgnav/heartbeat_t.hpp"

namespace rgnav::testing {

// The udpm URL multi-process tests use inside their private namespace (see in_netns.sh):
// ttl=0 keeps traffic on the host even if run outside one; the receive buffer fits ~1 MB
// messages.
std::string test_udpm_url();

// True when running inside a namespace made by in_netns.sh (RGNAV_NETNS=1).
bool in_private_netns();

// Skips the current gtest unless in_netns.sh set up a private network namespace: multicast
// tests must never run on the host network.
#define RGNAV_REQUIRE_NETNS()                                                                    \
  do {                                                                                           \
    if (!::rgnav::testing::in_private_netns())                                                   \
      GTEST_SKIP() << "needs a private network namespace: run via tests/support/in_netns.sh " \
                      "(ctest does)";                                                            \
  } while (0)

struct ReceivedHeartbeat
{
  heartbeat_t msg;
  std::chrono::steady_clock::time_point received;
};

class HeartbeatWatch
{
 public:
  explicit HeartbeatWatch(const std::string& url, const std::string& channel = "HEARTBEAT");
  // Pumps the bus until a heartbeat from `name` (and pid, if > 0) arrives; returns it.
  std::optional<heartbeat_t> wait_for(const std::string& name, std::chrono::milliseconds timeout,
                                      int32_t pid = 0);
  // Pumps the bus until pred(heartbeat) holds for one from `name`.
  std::optional<heartbeat_t> wait_until(const std::string& name, std::chrono::milliseconds timeout,
                                        const std::function<bool(const heartbeat_t&)>& pred);
  // Pumps for `duration` and returns every heartbeat seen since construction or clear().
  const std::vector<ReceivedHeartbeat>& collect(std::chrono::milliseconds duration);
  const std::vector<ReceivedHeartbeat>& seen() const { return seen_; }
  std::vector<ReceivedHeartbeat> from(const std::string& name) const;
  void clear() { seen_.clear(); }
  int64_t dropped() const { return drops_.total(); }

 private:
  void pump(std::chrono::milliseconds max_wait);

  bus::LcmBus bus_;
  bus::DropCounter drops_;
  std::vector<ReceivedHeartbeat> seen_;
};

}  // namespace rgnav::testing
