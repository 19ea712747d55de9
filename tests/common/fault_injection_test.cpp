// The runtime's fault-injection hook: off unless enabled, acts only on faults addressed to its
// process (name, and pid unless 0), survives malformed messages, and a busy loop really keeps
// the dispatching thread for its duration. Only lower bounds, or 5 s against microseconds: no
// threshold a loaded machine could cross.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>

#include "bus/fake_bus.h"
#include "bus/typed.h"
#include "rgnav/fault_inject_t.hpp"
#include "runtime/fault_injection.h"

namespace rgnav::runtime {
namespace {

using Clock = std::chrono::steady_clock;

fault_inject_t busy(const std::string& target, int32_t pid, int32_t ms)
{
  fault_inject_t f;
  f.utime = 1;
  f.target = target;
  f.pid = pid;
  f.fault = fault_inject_t::FAULT_BUSY_LOOP;
  f.duration_ms = ms;
  return f;
}

// How long publishing `f` (delivered synchronously by the FakeBus) kept this thread.
double held_ms(bus::FakeBus& bus, const fault_inject_t& f)
{
  const auto t0 = Clock::now();
  EXPECT_TRUE(bus::publish(bus, kFaultInjectChannel, f));
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

TEST(FaultInjection, OffUnlessTheEnvironmentSaysSo)
{
  unsetenv(kFaultInjectionEnv);
  EXPECT_FALSE(fault_injection_enabled());
  setenv(kFaultInjectionEnv, "0", 1);
  EXPECT_FALSE(fault_injection_enabled());
  setenv(kFaultInjectionEnv, "1", 1);
  EXPECT_TRUE(fault_injection_enabled());
  unsetenv(kFaultInjectionEnv);
}

TEST(FaultInjection, DisabledProcessDoesNotListen)
{
  bus::FakeBus bus;
  EXPECT_FALSE(attach_fault_injection(bus, "lld", false));
  EXPECT_LT(held_ms(bus, busy("lld", 0, 5000)), 5000.0);
}

TEST(FaultInjection, BusyLoopKeepsTheLoopForItsDuration)
{
  bus::FakeBus bus;
  ASSERT_TRUE(attach_fault_injection(bus, "lld", true));
  EXPECT_GE(held_ms(bus, busy("lld", 0, 120)), 120.0);
  EXPECT_GE(held_ms(bus, busy("lld", static_cast<int32_t>(getpid()), 60)), 60.0);
}

TEST(FaultInjection, OnlyFaultsAddressedToThisProcess)
{
  bus::FakeBus bus;
  ASSERT_TRUE(attach_fault_injection(bus, "lld", true));
  // Another process's name, or this name with another pid (an older instance): ignored.
  EXPECT_LT(held_ms(bus, busy("base_driver", 0, 5000)), 5000.0);
  EXPECT_LT(held_ms(bus, busy("lld", static_cast<int32_t>(getpid()) + 1, 5000)), 5000.0);
}

TEST(FaultInjection, MalformedMessagesAreDropped)
{
  bus::FakeBus bus;
  ASSERT_TRUE(attach_fault_injection(bus, "lld", true));
  const uint8_t junk[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  EXPECT_TRUE(bus.publish(kFaultInjectChannel, junk, sizeof junk));  // no crash, no loop
  EXPECT_GE(held_ms(bus, busy("lld", 0, 30)), 30.0);                  // still listening
}

}  // namespace
}  // namespace rgnav::runtime
