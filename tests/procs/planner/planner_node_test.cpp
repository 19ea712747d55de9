// The planner process over a FakeBus on the hand-made two-room RG map (room_a region 1, room_b
// region 2 behind the door, gateway 1): goals by id and by name give GLOBAL_PATH OK and TARGETS
// in the odometry frame; the goal is reached, cancelled, or has no path with a reason; the
// scan mapper's pose stands in while there is no localizer; odometry keeps a standing robot's
// pose fresh; malformed and hostile input is dropped and counted; bad config is refused naming
// file and key; the state file carries learned costs, names and the running goal across a
// restart.
#include "planner/planner_node.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <thread>

#include "bus/typed.h"
#include "child_process.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "fake_bus_node.h"
#include "msg/conversions.h"
#include "planner/planner_state.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/global_path_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/target_list_t.hpp"
#include "two_room_map.h"

namespace rgnav::planner {
namespace {

using geometry::Pose2;

constexpr int64_t kT0 = 1'700'000'000'000'000;
// The odometry frame: where the robot was when its base driver started, map (1, 1.5, 0).
const Pose2 kMapFromOdom(1.0, 1.5, 0.0);

PlannerNodeConfig shipped_config()
{
  const auto cfg = config::Config::load(RGNAV_SOURCE_DIR "/config/planner.yaml");
  const auto robot = config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml");
  auto c = load_planner_node_config(cfg, robot);
  runtime::load_node_options(cfg.section("node"), "planner");   // the runtime's keys, so that finish() sees every key read
  cfg.finish();
  return c;
}

struct Fixture
{
  testing::TwoRoomWorld world = testing::two_room_world();
  PlannerNodeConfig config = shipped_config();
  testing::FakeBusNode fake{"planner"};
  std::unique_ptr<PlannerNode> node;
  int64_t t = kT0;
  int64_t odometry_seq = 0;

  explicit Fixture(PlannerFiles files = {}) { node = std::make_unique<PlannerNode>(*fake.node, config, files); }

  void publish_map() { ASSERT_TRUE(bus::publish(*fake.bus, "RG_MAP", rgmap::to_msg(world.map))); }

  // The localizer's estimate: map_from_base placed in `region` (its frame from the map).
  void pose(const Pose2& map_from_base, int64_t region = 0, float confidence = 0.9f)
  {
    if (region == 0) region = map_from_base.x() < 4.0 ? world.room_a : world.room_b;
    region_pose_t m{};
    m.utime = t;
    m.scan_id = t / 1000;
    m.region_id = region;
    m.region_from_base = msg::to_msg(world.map.region(region)->map_from_region.inverse() * map_from_base);
    m.map_from_base = msg::to_msg(map_from_base);
    m.odom_from_base = msg::to_msg(kMapFromOdom.inverse() * map_from_base);
    m.covariance[0] = m.covariance[4] = 0.01;
    m.covariance[8] = 0.001;
    m.confidence = confidence;
    ASSERT_TRUE(bus::publish(*fake.bus, "POSE", m));
  }

  void odometry(const Pose2& map_from_base)
  {
    odometry_t m{};
    m.utime = t;
    m.seq = ++odometry_seq;
    m.odom_from_base = msg::to_msg(kMapFromOdom.inverse() * map_from_base);
    m.status = odometry_t::STATUS_SIMULATED;
    ASSERT_TRUE(bus::publish(*fake.bus, "ODOMETRY", m));
  }

  void goal(int64_t id, int64_t region, const std::string& name, std::optional<Pose2> at = std::nullopt)
  {
    nav_goal_t m{};
    m.utime = t;
    m.goal_id = id;
    m.region_id = region;
    m.region_name = name;
    m.has_pose = at.has_value();
    m.region_from_goal = msg::to_msg(at.value_or(Pose2()));
    m.position_tolerance = 0.3;
    m.heading_tolerance = M_PI;
    m.cancel = false;
    ASSERT_TRUE(bus::publish(*fake.bus, "NAV_GOAL", m));
  }

  void cancel(int64_t id)
  {
    nav_goal_t m{};
    m.utime = t;
    m.goal_id = id;
    m.position_tolerance = 0.3;
    m.heading_tolerance = M_PI;
    m.cancel = true;
    ASSERT_TRUE(bus::publish(*fake.bus, "NAV_GOAL", m));
  }

  void name(int64_t region, const std::string& n)
  {
    region_name_t m{};
    m.utime = t;
    m.region_id = region;
    m.name = n;
    ASSERT_TRUE(bus::publish(*fake.bus, "REGION_NAME", m));
  }

  std::vector<global_path_t> paths() const { return testing::decoded<global_path_t>(*fake.bus, "GLOBAL_PATH"); }
  std::vector<target_list_t> targets() const { return testing::decoded<target_list_t>(*fake.bus, "TARGETS"); }
  int64_t drops_on(const std::string& channel) const { return fake.node->drops().on_channel(channel); }
  heartbeat_t heartbeat()
  {
    fake.node->publish_heartbeat();
    return testing::decoded<heartbeat_t>(*fake.bus, "HEARTBEAT").back();
  }
};

// The targets of `list`, back in the map frame.
std::vector<Pose2> in_map(const target_list_t& list)
{
  std::vector<Pose2> out;
  for (const auto& p : list.odom_from_target) out.push_back(kMapFromOdom * msg::to_pose2(p));
  return out;
}

bool inside_rooms(const Eigen::Vector2d& p)
{
  const bool a = p.x() > 0.2 && p.x() < 3.8 && p.y() > 0.2 && p.y() < 2.8;
  const bool door = p.x() >= 3.8 && p.x() <= 4.2 && p.y() > 1.1 && p.y() < 1.9;
  const bool b = p.x() > 4.2 && p.x() < 8.8 && p.y() > -0.8 && p.y() < 2.8;
  return a || door || b;
}

TEST(PlannerNode, GoalByIdGivesAPathThroughTheDoorAndTargetsInTheOdometryFrame)
{
  Fixture f;
  f.publish_map();
  f.pose(Pose2(1.0, 1.5, 0.0));
  // Room B at (2.5, 1.0) of its frame: map (6.5, 1.0).
  f.goal(7, f.world.room_b, "", Pose2(2.5, 1.0, 0.0));
  const auto paths = f.paths();
  ASSERT_FALSE(paths.empty());
  const auto& p = paths.back();
  EXPECT_EQ(p.goal_id, 7);
  ASSERT_EQ(p.status, global_path_t::STATUS_OK) << p.reason;
  EXPECT_EQ(p.map_version, f.world.map.version);
  EXPECT_GT(p.cost, 5.0 / 0.6);   // 5.6 m at no more than the speed limit
  ASSERT_GE(p.nwaypoints, 3);
  EXPECT_EQ(p.waypoints.front().region_id, f.world.room_a);
  EXPECT_EQ(p.waypoints.back().region_id, f.world.room_b);
  int crossings = 0;
  for (const auto& w : p.waypoints) crossings += w.gateway_id == f.world.door;
  EXPECT_EQ(crossings, 2);   // the door's crossing point ends room_a's leg and begins room_b's
  EXPECT_LT(std::hypot(p.waypoints.back().pose.x - 2.5, p.waypoints.back().pose.y - 1.0), 0.3);

  const auto lists = f.targets();
  ASSERT_FALSE(lists.empty());
  const auto& t = lists.back();
  EXPECT_EQ(t.goal_id, 7);
  ASSERT_GE(t.ntargets, 2);
  EXPECT_GT(t.max_speed, 0.f);
  EXPECT_LE(t.max_speed, 0.6f + 1e-6f);
  const auto targets = in_map(t);
  for (const auto& q : targets) EXPECT_TRUE(inside_rooms(q.translation())) << q.x() << ", " << q.y();
  // Spaced for collision avoidance (0.5 - 2 m) and leading away from the robot toward the door.
  Eigen::Vector2d prev(1.0, 1.5);
  for (const auto& q : targets) {
    EXPECT_LE((q.translation() - prev).norm(), 2.0 + 1e-6);
    prev = q.translation();
  }
  EXPECT_GT(targets.back().x(), 3.0);
  if (t.final_is_goal) {
    EXPECT_LT((targets.back().translation() - Eigen::Vector2d(6.5, 1.0)).norm(), 0.3);
  }
  EXPECT_EQ(f.fake.node->drops().total(), 0);
  const auto hb = f.heartbeat();
  EXPECT_EQ(hb.state, heartbeat_t::STATE_RUNNING) << hb.status;
  EXPECT_NE(hb.status.find("goal 7 active"), std::string::npos) << hb.status;
  EXPECT_NE(hb.status.find("replans"), std::string::npos) << hb.status;
}

TEST(PlannerNode, GoalByNameAndByAnOperatorsNameReachedAndCancelled)
{
  Fixture f;
  f.publish_map();
  f.pose(Pose2(1.0, 1.5, 0.0));
  f.goal(1, 0, "ROOM_B");   // names compare without regard to case; anywhere suitable in it
  ASSERT_FALSE(f.paths().empty());
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
  EXPECT_EQ(f.paths().back().waypoints.back().region_id, f.world.room_b);
  // The operator renames room_b; a goal by the new name goes there at once.
  f.name(f.world.room_b, "Lab 2");
  EXPECT_EQ(f.node->names().at(f.world.room_b), "Lab 2");
  f.goal(2, 0, "lab 2", Pose2(1.0, 0.0, 0.0));
  EXPECT_EQ(f.paths().back().goal_id, 2);
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
  // There: reached, and an empty target list stops collision avoidance.
  f.t += 500'000;
  f.pose(Pose2(5.05, 0.0, 0.3), f.world.room_b);
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_GOAL_REACHED);
  EXPECT_EQ(f.targets().back().ntargets, 0);
  EXPECT_EQ(f.targets().back().goal_id, 2);
  // A name nobody gave: no path, with the reason.
  f.goal(3, 0, "kitchen");
  EXPECT_EQ(f.paths().back().goal_id, 3);
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_NO_PATH);
  EXPECT_NE(f.paths().back().reason.find("kitchen"), std::string::npos) << f.paths().back().reason;
  // Cancelled: another id's cancel changes nothing, this one's ends it.
  f.goal(4, f.world.room_a, "", Pose2(2.0, 2.0, 0.0));
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_OK);
  f.cancel(99);
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_OK);
  f.cancel(4);
  EXPECT_EQ(f.paths().back().goal_id, 4);
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_CANCELLED);
  EXPECT_EQ(f.targets().back().ntargets, 0);
  EXPECT_EQ(f.fake.node->drops().total(), 0);
}

TEST(PlannerNode, TheScanMappersPoseInTheCurrentRegionWhileThereIsNoLocalizer)
{
  Fixture f;
  f.publish_map();   // current region: room_a
  slam_pose_t s{};
  s.utime = f.t;
  s.scan_id = 1;
  s.map_from_base = msg::to_msg(Pose2(1.0, 1.5, 0.0));
  s.map_from_odom = msg::to_msg(kMapFromOdom);
  ASSERT_TRUE(bus::publish(*f.fake.bus, "SLAM_POSE", s));
  f.goal(5, f.world.room_b, "", Pose2(2.5, 1.0, 0.0));
  ASSERT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
  const auto targets = in_map(f.targets().back());
  ASSERT_FALSE(targets.empty());
  for (const auto& q : targets) EXPECT_TRUE(inside_rooms(q.translation())) << q.x() << ", " << q.y();
}

TEST(PlannerNode, TheScanMappersPoseHeardBeforeTheFirstMapIsPlacedInIt)
{
  // A robot standing at its start: the scan mapper's first pose comes before the kernel's first
  // map, and no other comes until the robot moves.
  Fixture f;
  slam_pose_t s{};
  s.utime = f.t;
  s.scan_id = 1;
  s.map_from_base = msg::to_msg(Pose2(1.0, 1.5, 0.0));
  s.map_from_odom = msg::to_msg(kMapFromOdom);
  ASSERT_TRUE(bus::publish(*f.fake.bus, "SLAM_POSE", s));
  f.publish_map();
  f.goal(5, f.world.room_b, "", Pose2(2.5, 1.0, 0.0));
  ASSERT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
  EXPECT_FALSE(f.targets().empty());
}

TEST(PlannerNode, OdometryKeepsAStandingRobotsPoseFresh)
{
  Fixture f;
  f.publish_map();
  f.pose(Pose2(1.0, 1.5, 0.0));
  // The localizer says nothing more while the robot stands (it updates when it moves); the
  // goal comes 5 s later, past the pose timeout: odometry carries the pose to now.
  for (int i = 0; i < 50; ++i) {
    f.t += 100'000;
    f.odometry(Pose2(1.0, 1.5, 0.0));
  }
  f.goal(6, f.world.room_b, "", Pose2(2.5, 1.0, 0.0));
  ASSERT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
  const size_t lists = f.targets().size();
  ASSERT_GT(lists, 0u);
  EXPECT_GE(f.targets().back().ntargets, 2);
  // It drives off on odometry: targets keep coming (re-sent every resend period).
  for (int i = 1; i <= 20; ++i) {
    f.t += 100'000;
    f.odometry(Pose2(1.0 + 0.05 * i, 1.5, 0.0));
  }
  EXPECT_GE(f.targets().size(), lists + 3);
  EXPECT_GE(f.targets().back().ntargets, 1);
  EXPECT_EQ(f.heartbeat().state, heartbeat_t::STATE_RUNNING);
}

TEST(PlannerNode, MalformedAndHostileInputIsDroppedAndCounted)
{
  Fixture f;
  f.publish_map();
  f.pose(Pose2(1.0, 1.5, 0.0));
  const auto raw = [&](const std::string& channel, const auto& m) {
    std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
    ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
    ASSERT_TRUE(f.fake.bus->publish(channel, buf.data(), buf.size()));
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // POSE: NaN (wire check), region 0, 20 km away, a stamp 100 s ahead (held: it moves the
  // robot's time only when a second input confirms it).
  region_pose_t p{};
  p.utime = f.t;
  p.region_id = f.world.room_a;
  p.confidence = 0.9f;
  p.region_from_base.x = nan;
  raw("POSE", p);
  p.region_from_base.x = 1.0;
  p.region_id = 0;
  raw("POSE", p);
  p.region_id = f.world.room_a;
  p.region_from_base.x = 2e4;
  raw("POSE", p);
  p.region_from_base.x = 1.0;
  p.utime = f.t + 100'000'000;
  raw("POSE", p);
  EXPECT_EQ(f.drops_on("POSE"), 4);
  EXPECT_EQ(f.node->robot_utime(), f.t);
  // NAV_GOAL: no tolerance (semantic check), a 100 character name, goal id 0.
  nav_goal_t g{};
  g.utime = f.t;
  g.goal_id = 9;
  g.region_id = f.world.room_b;
  g.position_tolerance = 0;
  g.heading_tolerance = M_PI;
  raw("NAV_GOAL", g);
  g.position_tolerance = 0.3;
  g.region_id = 0;
  g.region_name = std::string(100, 'a');
  raw("NAV_GOAL", g);
  g.region_name = "room_b";
  g.goal_id = 0;
  raw("NAV_GOAL", g);
  EXPECT_EQ(f.drops_on("NAV_GOAL"), 3);
  EXPECT_FALSE(f.node->planner().goal().has_value());
  // REGION_NAME: a control character, only digits (semantic checks), an unknown region,
  // another region's name (the node).
  region_name_t n{};
  n.utime = f.t;
  n.region_id = f.world.room_b;
  n.name = "lab\n";
  raw("REGION_NAME", n);
  n.name = "123";
  raw("REGION_NAME", n);
  n.name = "lab";
  n.region_id = 42;
  raw("REGION_NAME", n);
  n.region_id = f.world.room_b;
  n.name = "Room_A";
  raw("REGION_NAME", n);
  EXPECT_EQ(f.drops_on("REGION_NAME"), 4);
  EXPECT_TRUE(f.node->names().empty());
  // CA_STATUS: an unknown mode (enum check); SLAM_POSE: infinity; ODOMETRY: negative stamp;
  // RG_MAP: garbage; a map whose gateway leads nowhere (refused by the conversion).
  ca_status_t c{};
  c.utime = f.t;
  c.mode = 9;
  raw("CA_STATUS", c);
  slam_pose_t s{};
  s.utime = f.t;
  s.map_from_base.theta = std::numeric_limits<double>::infinity();
  raw("SLAM_POSE", s);
  odometry_t o{};
  o.utime = -5;
  o.seq = 1;
  raw("ODOMETRY", o);
  const uint8_t garbage[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  f.fake.bus->publish("RG_MAP", garbage, sizeof garbage);
  rg_map_t broken = rgmap::to_msg(f.world.map);
  broken.version = 2;
  broken.gateways[0].region_b = 77;
  ASSERT_TRUE(bus::publish(*f.fake.bus, "RG_MAP", broken));
  EXPECT_EQ(f.drops_on("CA_STATUS"), 1);
  EXPECT_EQ(f.drops_on("SLAM_POSE"), 1);
  EXPECT_EQ(f.drops_on("ODOMETRY"), 1);
  EXPECT_EQ(f.drops_on("RG_MAP"), 2);
  EXPECT_EQ(f.fake.node->drops().total(), 16);
  // None of it changed what the planner holds; a good goal still works.
  f.goal(10, f.world.room_b, "", Pose2(2.5, 1.0, 0.0));
  EXPECT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
  EXPECT_EQ(f.paths().back().map_version, f.world.map.version);
  EXPECT_EQ(f.heartbeat().messages_dropped, 16);
}

TEST(PlannerNode, AStampFarAheadCountsOnceASecondInputConfirmsIt)
{
  Fixture f;
  f.publish_map();
  f.pose(Pose2(1.0, 1.5, 0.0));
  f.t += 60'000'000;   // the robot stood a minute with nothing on the bus
  f.pose(Pose2(1.0, 1.5, 0.0));
  EXPECT_EQ(f.drops_on("POSE"), 1);
  f.t += 100'000;
  f.pose(Pose2(1.0, 1.5, 0.0));
  EXPECT_EQ(f.drops_on("POSE"), 1);
  EXPECT_EQ(f.node->robot_utime(), f.t);
}

TEST(PlannerNode, ConfigOutOfRangeIsRefusedNamingFileAndKey)
{
  const auto robot = config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml");
  const auto refused = [&](const std::string& yaml, const std::string& key) {
    const auto cfg = config::Config::parse(yaml, "bad_planner.yaml");
    try {
      load_planner_node_config(cfg, robot);
      cfg.finish();
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const config::ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad_planner.yaml"), std::string::npos) << what;
      EXPECT_NE(what.find(key), std::string::npos) << what;
    }
  };
  refused("grid:\n  resolution_m: 0\n", "grid.resolution_m");
  refused("execution:\n  target_spacing_min_m: 1.0\n  target_spacing_max_m: 0.5\n", "execution.target_spacing_max_m");
  refused("global:\n  learning_rate: 2\n", "global.learning_rate");
  refused("persist:\n  period_s: -1\n", "persist.period_s");
  refused("channels:\n  targets: \"\"\n", "channels.targets");
  refused("execution:\n  max_sped_mps: 0.5\n", "execution.max_sped_mps");
  refused("grid:\n  robot_radius_m: 0.3\n", "grid.robot_radius_m");   // the robot description's, not here
  // The robot description decides the radius and caps the speed.
  auto slow = robot;
  slow.radius = 0.4;
  slow.drive.max_v = 0.3;
  const auto c = load_planner_node_config(config::Config::parse("", "planner.yaml"), slow);
  EXPECT_DOUBLE_EQ(c.options.planner.grid.robot_radius, 0.4);
  EXPECT_DOUBLE_EQ(c.options.planner.execution.max_speed, 0.3);
}

TEST(PlannerNode, ShippedConfigHasTheHeadersDefaults)
{
  // config/planner.yaml documents the defaults of planner_options.h: loading it changes nothing.
  const auto c = shipped_config();
  const PlannerOptions d;
  const auto& o = c.options.planner;
  EXPECT_EQ(o.grid.resolution, d.grid.resolution);
  EXPECT_EQ(o.grid.clearance_margin, d.grid.clearance_margin);
  EXPECT_EQ(o.grid.comfort_width, d.grid.comfort_width);
  EXPECT_EQ(o.grid.wall_cost, d.grid.wall_cost);
  EXPECT_EQ(o.grid.cost_levels, d.grid.cost_levels);
  EXPECT_EQ(o.grid.adapt_distance, d.grid.adapt_distance);
  EXPECT_EQ(o.grid.comfort_cost, d.grid.comfort_cost);
  EXPECT_EQ(o.grid.neighbour_margin, d.grid.neighbour_margin);
  EXPECT_EQ(o.grid.passage_depth, d.grid.passage_depth);
  EXPECT_EQ(o.grid.beyond_known_reach, d.grid.beyond_known_reach);
  EXPECT_EQ(o.grid.unknown_overlap, d.grid.unknown_overlap);
  EXPECT_EQ(o.global.crossing_reach, d.global.crossing_reach);
  EXPECT_EQ(o.execution.max_accel, d.execution.max_accel);
  EXPECT_EQ(o.execution.max_omega, d.execution.max_omega);
  EXPECT_EQ(o.global.nominal_speed, d.global.nominal_speed);
  EXPECT_EQ(o.global.crossing_time, d.global.crossing_time);
  EXPECT_EQ(o.global.door_extra_time, d.global.door_extra_time);
  EXPECT_EQ(o.global.door_failed_time, d.global.door_failed_time);
  EXPECT_EQ(o.global.door_passed_time, d.global.door_passed_time);
  EXPECT_EQ(o.global.closed_retry_s, d.global.closed_retry_s);
  EXPECT_EQ(o.global.learning_rate, d.global.learning_rate);
  EXPECT_EQ(o.execution.target_spacing_min, d.execution.target_spacing_min);
  EXPECT_EQ(o.execution.target_spacing_max, d.execution.target_spacing_max);
  EXPECT_EQ(o.execution.targets_ahead_m, d.execution.targets_ahead_m);
  EXPECT_EQ(o.execution.resend_period_s, d.execution.resend_period_s);
  EXPECT_EQ(o.execution.max_speed, d.execution.max_speed);
  EXPECT_EQ(o.execution.min_replan_period_s, d.execution.min_replan_period_s);
  EXPECT_EQ(o.execution.blocked_after_s, d.execution.blocked_after_s);
  EXPECT_EQ(o.execution.gateway_reach_m, d.execution.gateway_reach_m);
  EXPECT_EQ(o.execution.closed_after_s, d.execution.closed_after_s);
  EXPECT_EQ(o.execution.switch_gain, d.execution.switch_gain);
  EXPECT_EQ(o.execution.off_route_m, d.execution.off_route_m);
  EXPECT_EQ(o.execution.pose_timeout_s, d.execution.pose_timeout_s);
  EXPECT_EQ(c.options.persist_period_s, PlannerNodeOptions{}.persist_period_s);
  const PlannerNodeOptions::Channels ch;
  EXPECT_EQ(c.options.channels.rg_map, ch.rg_map);
  EXPECT_EQ(c.options.channels.targets, ch.targets);
  EXPECT_EQ(c.options.channels.ca_status, ch.ca_status);
}

TEST(PlannerNode, StateFileCarriesLearnedCostsNamesAndTheRunningGoalAcrossARestart)
{
  testing::TempDir dir("planner_node");
  const auto world = testing::two_room_world();
  testing::write_rgmap_json(world.map, dir.file("map"));
  const PlannerFiles files{dir.file("map"), dir.file("state/planner.json")};
  nlohmann::json learned;
  {
    Fixture f(files);
    f.pose(Pose2(1.0, 1.5, 0.0));
    f.name(f.world.room_b, "lab");
    f.goal(21, 0, "lab", Pose2(3.0, 1.0, 0.0));
    ASSERT_EQ(f.paths().back().status, global_path_t::STATUS_OK) << f.paths().back().reason;
    // The goal is saved at once, or (the name was saved just before: at most 5 saves a
    // second) at the node's next turn: a kill now would not lose it.
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    f.fake.node->spin_once(std::chrono::milliseconds(150));
    const auto saved = load_planner_state(files.state_file);
    ASSERT_TRUE(saved.has_value());
    ASSERT_TRUE(saved->goal.has_value());
    EXPECT_EQ(saved->goal->goal_id, 21);
    EXPECT_EQ(saved->names.at(f.world.room_b), "lab");
    // Drive through the door (poses every 0.2 s along y = 1.5): the crossing is timed.
    for (double x = 1.2; x <= 5.6; x += 0.1) {
      f.t += 200'000;
      f.pose(Pose2(x, 1.5, 0.0));
    }
    EXPECT_GT(f.node->planner().global().costs().changes(), 0);
    learned = f.node->planner().global().costs().to_json();
    EXPECT_EQ(f.node->planner().status(), GoalStatus::kActive);
  }
  // The node's stop saved everything.
  const auto saved = load_planner_state(files.state_file);
  ASSERT_TRUE(saved.has_value());
  EXPECT_EQ(saved->costs, learned);
  ASSERT_TRUE(saved->goal.has_value());
  EXPECT_EQ(saved->goal->goal_id, 21);

  Fixture g(files);
  ASSERT_TRUE(g.node->resumed_goal().has_value());
  EXPECT_EQ(g.node->resumed_goal()->goal_id, 21);
  ASSERT_TRUE(g.node->planner().goal().has_value());
  EXPECT_EQ(g.node->planner().goal()->goal_id, 21);
  EXPECT_EQ(g.node->planner().global().costs().to_json(), learned);
  EXPECT_EQ(g.node->names().at(world.room_b), "lab");
  // It says so at once (before any pose): GLOBAL_PATH for the resumed goal.
  ASSERT_FALSE(g.paths().empty());
  EXPECT_EQ(g.paths().back().goal_id, 21);
  EXPECT_NE(g.paths().back().status, global_path_t::STATUS_CANCELLED);
  // The robot is where it stopped: the goal is planned from there and reached.
  g.t = kT0 + 60'000'000;
  g.pose(Pose2(5.6, 1.5, 0.0));
  EXPECT_EQ(g.paths().back().status, global_path_t::STATUS_OK) << g.paths().back().reason;
  g.t += 200'000;
  g.pose(Pose2(7.0, 1.0, 0.0));
  EXPECT_EQ(g.paths().back().status, global_path_t::STATUS_GOAL_REACHED);
  // A reached goal is no goal to resume.
  g.node.reset();
  const auto after = load_planner_state(files.state_file);
  ASSERT_TRUE(after.has_value());
  EXPECT_FALSE(after->goal.has_value());
  EXPECT_EQ(after->names.at(world.room_b), "lab");
}

TEST(PlannerNode, ADamagedStateFileIsSetAsideAndAMissingMapRefused)
{
  testing::TempDir dir("planner_node");
  testing::write_rgmap_json(testing::two_room_world().map, dir.file("map"));
  std::ofstream(dir.file("state")) << "garbage";
  {
    Fixture f(PlannerFiles{dir.file("map"), dir.file("state")});
    EXPECT_FALSE(f.node->resumed_goal().has_value());
    EXPECT_TRUE(std::ifstream(dir.file("state.damaged")).good());
  }
  EXPECT_TRUE(load_planner_state(dir.file("state")).has_value());   // a good one was written on exit
  EXPECT_THROW({ Fixture missing(PlannerFiles{dir.file("missing"), ""}); }, config::ConfigError);
}

}  // namespace
}  // namespace rgnav::planner
