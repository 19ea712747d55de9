#include <gtest/gtest.h>

#include "bus/typed.h"
#include "fake_bus_node.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "sim/sim_node.h"
#include "sim/world_yaml.h"

namespace rgnav::sim {
namespace {

using rgnav::testing::decoded;

TEST(SimNode, DirectModePublishesScansOdometryAndTruthAndHonoursDeadlines)
{
  rgnav::testing::FakeBusNode fake("rgnav_sim");
  bus::FakeBus& bus = *fake.bus;
  runtime::Node& node = *fake.node;
  SimulatorOptions options;
  auto sim = std::make_unique<Simulator>(load_world(std::string(RGNAV_SOURCE_DIR) + "/config/worlds/office.yaml"), options);
  const Pose2 start = sim->truth();
  SimNode sim_node(node, std::move(sim), ProcessOptions{}, SimChannels{}, /*manual=*/true);

  sim_node.advance(std::chrono::microseconds(1'000'000));
  auto scans = decoded<laser_scan_t>(bus, "LASER_FRONT");
  auto odom = decoded<odometry_t>(bus, "ODOMETRY");
  auto truth = decoded<odometry_t>(bus, "SIM_TRUTH");
  EXPECT_EQ(scans.size(), 75u);
  EXPECT_EQ(odom.size(), 50u);
  ASSERT_EQ(truth.size(), 50u);
  EXPECT_EQ(scans[0].nranges, 181);
  EXPECT_EQ(scans[0].sensor, "laser_front");
  EXPECT_EQ(odom.back().status, odometry_t::STATUS_SIMULATED);
  EXPECT_EQ(truth.back().odom_from_base.x, start.x);  // no command: standing still
  EXPECT_EQ(truth.back().odom_from_base.y, start.y);

  // A command with a 0.5 s deadline, stamped with the simulator's message time.
  velocity_cmd_t cmd;
  cmd.utime = odom.back().utime;
  cmd.seq = 1;
  cmd.v = 0.5;
  cmd.omega = 0.0;
  cmd.deadline_us = 500'000;
  cmd.source = "test";
  ASSERT_TRUE(bus::publish(bus, "BASE_CMD", cmd));
  bus.clear();
  sim_node.advance(std::chrono::microseconds(3'000'000));
  truth = decoded<odometry_t>(bus, "SIM_TRUTH");
  ASSERT_FALSE(truth.empty());
  // Accelerated for 0.5 s (to 0.4 m/s, 0.1 m), then stopped within 0.5 s (another 0.1 m);
  // the start heading is +y.
  EXPECT_NEAR(truth.back().odom_from_base.y - start.y, 0.2, 0.01);
  EXPECT_EQ(truth.back().v, 0.0);
  odom = decoded<odometry_t>(bus, "ODOMETRY");
  EXPECT_GT(odom.back().distance, 0.15);
}

}  // namespace
}  // namespace rgnav::sim
