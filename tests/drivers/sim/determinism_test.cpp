#include <gtest/gtest.h>

#include "bus/typed.h"
#include "msg/conversions.h"
#include "sim/sim_conversions.h"
#include "sim/simulator.h"
#include "sim/step_order.h"
#include "sim/world_yaml.h"

namespace rgnav::sim {
namespace {

// Drives a fixed command schedule (a function of message time only) through the office
// world with noise everywhere, and returns every published message encoded, in order.
std::vector<uint8_t> run(uint64_t seed, int steps)
{
  SimulatorOptions o;
  o.seed = seed;
  o.laser.noise_sigma = 0.02;
  o.odometry.sigma_translation = 0.02;
  o.odometry.sigma_rotation = 0.02;
  o.odometry.scale_translation = 0.01;
  Simulator sim(load_world(std::string(RGNAV_SOURCE_DIR) + "/config/worlds/office.yaml"), o);
  TimedCommandSource cmd;
  sim.set_command_source(&cmd);
  std::vector<uint8_t> bytes;
  auto append = [&bytes](const auto& msg) {
    std::vector<uint8_t> buf;
    std::string why;
    ASSERT_TRUE(bus::encode(msg, &buf, &why)) << why;
    bytes.insert(bytes.end(), buf.begin(), buf.end());
  };
  for (int k = 0; k < steps; ++k) {
    // Weave through the lobby: forward, with a turn rate that changes every second.
    const double omega = ((k / 75) % 2 == 0) ? 0.4 : -0.4;
    cmd.set(sim.now_utime(), {0.4, omega}, 200'000);
    const StepOutput out = sim.step(std::chrono::microseconds(13333));
    for (const auto& s : out.scans) append(msg::to_msg(s));
    for (const auto& s : out.odometry) {
      append(to_odometry_msg(s));
      append(to_truth_msg(s));
    }
  }
  return bytes;
}

TEST(Determinism, SameWorldSeedAndCommandsGiveIdenticalBytes)
{
  const auto a = run(17, 300);
  const auto b = run(17, 300);
  ASSERT_GT(a.size(), 100000u);
  EXPECT_TRUE(a == b) << "two runs with the same seed differ";
  const auto c = run(18, 300);
  EXPECT_FALSE(a == c) << "the seed has no effect";
}

TEST(StepOrder, EachScanComesAfterTheOdometryUpToItsTimeAndTheRestLast)
{
  StepOutput out;
  for (int64_t t : {1, 5, 9, 12}) {
    OdometrySample o;
    o.utime = t;
    out.odometry.push_back(o);
  }
  for (int64_t t : {4, 9}) {
    sensors::LaserScan s;
    s.utime = t;
    out.scans.push_back(s);
  }
  std::string order;
  in_time_order(
      out, [&](const OdometrySample& o) { order += "o" + std::to_string(o.utime) + " "; },
      [&](const sensors::LaserScan& s) { order += "s" + std::to_string(s.utime) + " "; });
  EXPECT_EQ(order, "o1 s4 o5 o9 s9 o12 ");
}

}  // namespace
}  // namespace rgnav::sim
