// The node adapter over a FakeBus with the emulated LMS on a pty: scans become valid
// laser_scan_t on the configured channel with strictly increasing ids, and the heartbeat
// status carries the link state and error counters. Also the options loader.
#include <gtest/gtest.h>

#include "bus/typed.h"
#include "driver_test_support.h"
#include "fake_bus_node.h"
#include "laser_driver_node.h"
#include "lms2xx_emulator.h"
#include "rgnav/heartbeat_t.hpp"
#include "synthetic_room.h"

#ifndef SICK_CONFIG_FILE
#error "SICK_CONFIG_FILE must point at config/laser_driver.yaml"
#endif

namespace rgnav::drivers::sick {
namespace {

using namespace std::chrono_literals;

config::Config parse(const std::string& text) { return config::Config::parse(text, "test.yaml"); }

TEST(LaserDriverOptions, TheShippedConfigIsValid)
{
  const auto cfg = config::Config::load(SICK_CONFIG_FILE);
  runtime::load_node_options(cfg.section("node"), "laser_driver");
  const auto robot = config::load_robot_description_file(config::robot_path_beside(SICK_CONFIG_FILE, ""));
  const auto o = load_laser_driver_options(cfg.section("laser_driver"), cfg.section("channels"), robot);
  EXPECT_NO_THROW(cfg.finish());
  EXPECT_EQ(o.channel, "LASER_FRONT");
  EXPECT_EQ(o.driver.desired_baud, 500000);
  EXPECT_EQ(o.driver.variant, (Variant{180, 100}));
  EXPECT_EQ(o.driver.units, Units::kMillimetres);
}

TEST(LaserDriverOptions, TheMountingIsTheRobotDescriptions)
{
  config::RobotDescription robot;
  robot.laser_front.base_from_laser = geometry::Pose2(0.3, -0.1, 0.5);
  robot.laser_front.height = 0.7;
  const auto cfg = parse("channels: {laser: LASER_FRONT}\nlaser_driver:\n  port: /dev/null\n");
  const auto o = load_laser_driver_options(cfg.section("laser_driver"), cfg.section("channels"), robot);
  EXPECT_DOUBLE_EQ(o.mounting.x_m, 0.3);
  EXPECT_DOUBLE_EQ(o.mounting.y_m, -0.1);
  EXPECT_DOUBLE_EQ(o.mounting.z_m, 0.7);
  EXPECT_DOUBLE_EQ(o.mounting.yaw_rad, 0.5);
  // A copy of it in the driver's config is refused (one robot description).
  const auto copied = parse("channels: {laser: LASER_FRONT}\nlaser_driver:\n  port: /dev/null\n  mounting: {x_m: 0.12}\n");
  load_laser_driver_options(copied.section("laser_driver"), copied.section("channels"), robot);
  EXPECT_THROW(copied.finish(), config::ConfigError);
}

TEST(LaserDriverOptions, RejectsImpossibleSettingsNamingTheKey)
{
  const std::string base = "channels: {laser: LASER_FRONT}\nlaser_driver:\n  port: /dev/null\n";
  auto load = [&](const std::string& extra) {
    const auto cfg = parse(base + extra);
    return load_laser_driver_options(cfg.section("laser_driver"), cfg.section("channels"), config::RobotDescription{});
  };
  EXPECT_NO_THROW(load(""));
  auto expect_error = [&](const std::string& extra, const std::string& key) {
    try {
      load(extra);
      ADD_FAILURE() << "accepted: " << extra;
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_error("  desired_baud: 115200\n", "desired_baud");
  expect_error("  angular_range_deg: 90\n", "angular_range_deg");
  expect_error("  angular_resolution_deg: 0.25\n", "angular_resolution_deg");  // 0.25° needs 100°
  expect_error("  units: dm\n", "units");
  expect_error("  password: short\n", "password");
  expect_error("  desired_baud: '9600'\n  silence_timeout_ms: 200\n", "silence_timeout_ms");
  EXPECT_THROW(
      {
        const auto cfg = parse("channels: {}\nlaser_driver: {}\n");
        load_laser_driver_options(cfg.section("laser_driver"), cfg.section("channels"), config::RobotDescription{});
      },
      config::ConfigError);  // port is required
}

TEST(ScanIdSequence, StrictlyIncreasingEvenForEqualOrOlderTimes)
{
  ScanIdSequence ids;
  EXPECT_EQ(ids.next(1000), 1000);
  EXPECT_EQ(ids.next(1000), 1001);
  EXPECT_EQ(ids.next(500), 1002);
  EXPECT_EQ(ids.next(5000), 5000);
  ScanIdSequence fresh;
  EXPECT_EQ(fresh.next(0), 1);  // 0 is never used
}

TEST(LaserDriverNode, PublishesValidScansAndReportsStatus)
{
  EmulatorOptions eo;
  eo.symlink_path = testing::unique_port_name("node");
  auto room = std::make_shared<SyntheticRoom>();
  Lms2xxEmulator emulator(eo, room);

  rgnav::testing::FakeBusNode n("laser_driver");
  bus::FakeBus* bus = n.bus;
  runtime::Node& node = *n.node;
  LaserDriverOptions o;
  o.driver = testing::fast_options(emulator.port_path());
  o.channel = "LASER_TEST";
  o.sensor = "laser_test";
  LaserDriverNode adapter(node, o);

  const auto end = std::chrono::steady_clock::now() + 10s;
  while (bus->published_on("LASER_TEST").size() < 20 && std::chrono::steady_clock::now() < end)
    node.spin_once(50ms);
  const auto published = rgnav::testing::decoded<laser_scan_t>(*bus, "LASER_TEST");
  ASSERT_GE(published.size(), 20u) << adapter.driver().status_text();

  int64_t last_id = 0, last_utime = 0;
  for (const auto& m : published) {
    EXPECT_GT(m.scan_id, last_id);
    EXPECT_GT(m.utime, last_utime);
    last_id = m.scan_id;
    last_utime = m.utime;
    EXPECT_EQ(m.sensor, "laser_test");
    ASSERT_EQ(m.nranges, 181);
    EXPECT_NEAR(m.ranges[0], room->range_at(-M_PI / 2), 0.0006);  // right wall
  }

  emulator.corrupt_next_scans(1);
  const size_t before = bus->published_on("LASER_TEST").size();
  while (bus->published_on("LASER_TEST").size() < before + 10 && std::chrono::steady_clock::now() < end + 5s)
    node.spin_once(50ms);
  node.publish_heartbeat();  // the status is refreshed every 200 ms; make sure one is out
  const auto hbs = bus->published_on("HEARTBEAT");
  ASSERT_FALSE(hbs.empty());
  heartbeat_t hb;
  std::string why;
  ASSERT_TRUE(bus::decode(hbs.back().data.data(), hbs.back().data.size(), &hb, &why)) << why;
  // Give the 200 ms status timer a chance to have run after the CRC error.
  const auto until = std::chrono::steady_clock::now() + 400ms;
  while (std::chrono::steady_clock::now() < until) node.spin_once(50ms);
  node.publish_heartbeat();
  const auto hbs2 = bus->published_on("HEARTBEAT");
  ASSERT_TRUE(bus::decode(hbs2.back().data.data(), hbs2.back().data.size(), &hb, &why)) << why;
  EXPECT_EQ(hb.state, heartbeat_t::STATE_RUNNING);
  EXPECT_NE(hb.status.find("streaming"), std::string::npos) << hb.status;
  EXPECT_NE(hb.status.find("crc errors 1"), std::string::npos) << hb.status;
}

}  // namespace
}  // namespace rgnav::drivers::sick
