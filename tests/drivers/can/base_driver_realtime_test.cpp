// BaseDriver in real time: its own thread on a VirtualCan client, the emulated drives on
// theirs, through the broker. Timing figures here are wall time on a possibly loaded machine:
// they are printed, and asserted only with generous bounds (the exact 200 ms requirement is
// asserted on simulated time in base_driver_sim_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "canopen/cia402.h"
#include "realtime_rig.h"

namespace rgnav::can::base {
namespace {

using namespace std::chrono_literals;
using PowerState = canopen::cia402::PowerState;

// A command source like lld's, for the rig's pump loops: sends `cmd` (valid 300 ms) to the
// driver at most every 40 ms.
std::function<void()> commanding(BaseDriver& driver, VelocityCommand cmd)
{
  auto last = std::chrono::steady_clock::now() - 1s;
  return [&driver, cmd, last]() mutable {
    if (std::chrono::steady_clock::now() - last < 40ms) return;
    driver.command(cmd, 300ms);
    last = std::chrono::steady_clock::now();
  };
}

TEST(BaseDriverRealtime, FollowsCommandsAndStopsWhenANodeIsLost)
{
  testing::RealtimeRig rig("rt-loss", 400ms);
  BaseDriver& driver = rig.start_driver();
  auto up = rig.pump_until([&] { return driver.snapshot().odometry.reason == "no command yet"; }, 5000ms);
  ASSERT_TRUE(up) << driver.snapshot().odometry.reason;
  std::printf("[ figures  ] real-time bring-up: %lld ms\n", static_cast<long long>(up->count()));

  auto command = commanding(driver, {0.4, 0.2});
  const double cpm = rig.options().translation.counts_per_unit;
  // Moving steadily and reported so (checked right before the cut: a scheduling stall on a
  // loaded machine can look like a lost node, and the driver then stops and recovers).
  BaseSnapshot s;
  auto moving = rig.pump_until(
      [&] {
        s = driver.snapshot();
        return rig.translation().actual_velocity() >= 0.4 * cpm - 1 && s.odometry.status == BaseStatus::kOk &&
               std::fabs(s.odometry.v - 0.4) < 1e-3 && s.odometry.distance > 0.05;
      },
      5000ms, command);
  ASSERT_TRUE(moving) << s.odometry.reason;
  EXPECT_NEAR(s.odometry.v, 0.4, 1e-3);
  EXPECT_NEAR(s.odometry.omega, 0.2, 1e-3);
  EXPECT_GT(s.odometry.distance, 0.05);
  EXPECT_GT(s.sample_wall_utime, 0);

  // The rotation drive is cut off the bus (its client disconnected by the broker).
  ASSERT_TRUE(rig.broker().disconnect("drive-3"));
  auto stopped = rig.pump_until([&] { return rig.translation().actual_velocity() == 0.0; }, 2000ms, command);
  ASSERT_TRUE(stopped) << "translation drive still moving";
  std::printf("[ figures  ] real-time: rotation node lost at 0.4 m/s -> translation at rest after %lld ms "
              "(wall time; simulated-time bound in base_driver_sim_test)\n",
              static_cast<long long>(stopped->count()));
  EXPECT_LT(*stopped, 600ms) << "generous real-time bound; the exact one is asserted in simulated time";
  s = driver.snapshot();
  EXPECT_EQ(s.odometry.status, BaseStatus::kFault);
  EXPECT_EQ(s.odometry.commanded.v, 0.0);

  // The node reconnects by itself (400 ms): recovery, and commands are followed again.
  auto back = rig.pump_until([&] { return driver.snapshot().odometry.status == BaseStatus::kOk; }, 5000ms, command);
  ASSERT_TRUE(back) << driver.snapshot().odometry.reason;
}

TEST(BaseDriverRealtime, BusOffIsReportedAndRecovered)
{
  testing::RealtimeRig rig("rt-busoff");
  BaseDriver& driver = rig.start_driver();
  ASSERT_TRUE(rig.pump_until([&] { return driver.snapshot().odometry.reason == "no command yet"; }, 5000ms));
  ASSERT_TRUE(rig.broker().bus_off("base_driver", 300ms));
  auto fault = rig.pump_until([&] { return driver.snapshot().odometry.reason == "CAN bus-off"; }, 1000ms);
  ASSERT_TRUE(fault) << driver.snapshot().odometry.reason;
  EXPECT_EQ(driver.snapshot().odometry.status, BaseStatus::kFault);
  // Silent master: the drives notice (heartbeat consumer) and leave operational.
  auto noticed = rig.pump_until([&] { return rig.translation().master_heartbeat_lost(); }, 1000ms);
  ASSERT_TRUE(noticed);
  auto back = rig.pump_until([&] { return driver.snapshot().odometry.reason == "no command yet"; }, 5000ms);
  ASSERT_TRUE(back) << driver.snapshot().odometry.reason;
  EXPECT_EQ(rig.translation().power_state(), PowerState::kOperationEnabled);
}

TEST(BaseDriverRealtime, StopWaitsForStandstillThenReleasesTheDrives)
{
  testing::RealtimeRig rig("rt-stop");
  rig.options().stop_timeout = 2000ms;
  BaseDriver& driver = rig.start_driver();
  ASSERT_TRUE(rig.pump_until([&] { return driver.snapshot().odometry.reason == "no command yet"; }, 5000ms));
  auto command = commanding(driver, {0.3, 0.0});
  const double cpm = rig.options().translation.counts_per_unit;
  ASSERT_TRUE(rig.pump_until([&] { return rig.translation().actual_velocity() >= 0.3 * cpm - 1; }, 3000ms, command));
  // stop() blocks until standstill: keep the emulators running meanwhile.
  std::atomic<bool> done{false};
  std::thread stopper([&] {
    driver.stop();
    done = true;
  });
  auto t = rig.pump_until([&] { return done.load(); }, 3000ms);
  stopper.join();
  ASSERT_TRUE(t);
  rig.pump_for(50ms);
  EXPECT_EQ(rig.translation().actual_velocity(), 0.0);
  EXPECT_EQ(rig.translation().nmt_state(), canopen::NmtState::kPreOperational);
}

}  // namespace
}  // namespace rgnav::can::base
