// The explorer process over a FakeBus on a hand-made one-room RG map (one_room.h): a goal for
// the planner once map and pose are there; NO_PATH for it leads to the next goal (the door the
// gateway detector saw) and, for the door, to setting it aside; the state file carries the
// gateway stack across a restart; a closed room is done at once and asked to be named;
// malformed and hostile input is dropped and counted; the process exits cleanly on SIGTERM.
#include "explorer/explorer_node.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <limits>
#include <thread>

#include "bus/typed.h"
#include "child_process.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "explorer/explorer_state.h"
#include "fake_bus_node.h"
#include "msg/conversions.h"
#include "one_room.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/explorer_status_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "rgnav/region_name_request_t.hpp"

namespace rgnav::explorer {
namespace {

using geometry::Pose2;

constexpr int64_t kT0 = 1'700'000'000'000'000;

ExplorerNodeConfig shipped_config()
{
  const auto cfg = config::Config::load(RGNAV_SOURCE_DIR "/config/explorer.yaml");
  const auto robot = config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml");
  auto c = load_explorer_node_config(cfg, robot);
  runtime::load_node_options(cfg.section("node"), "explorer");   // the runtime's keys, so that finish() sees every key read
  cfg.finish();
  return c;
}

// The node's message flow with goals of exploring from the first (no look behind first).
ExplorerNodeConfig no_look(ExplorerNodeConfig c)
{
  c.options.explorer.recovery.look_at_start = false;
  return c;
}

struct Fixture
{
  ExplorerNodeConfig config = no_look(shipped_config());
  testing::FakeBusNode fake{"explorer"};
  std::unique_ptr<ExplorerNode> node;
  int64_t t = kT0;
  Pose2 robot{1.0, 1.5, 0.0};

  explicit Fixture(ExplorerFiles files = {}) { node = std::make_unique<ExplorerNode>(*fake.node, config, files); }
  explicit Fixture(ExplorerNodeConfig c) : config(std::move(c)) { node = std::make_unique<ExplorerNode>(*fake.node, config); }

  void map(const rgmap::RgMap& m) { ASSERT_TRUE(bus::publish(*fake.bus, "RG_MAP", rgmap::to_msg(m))); }

  void slam_pose(const Pose2& map_from_base)
  {
    robot = map_from_base;
    slam_pose_t m{};
    m.utime = t;
    m.scan_id = t / 1000;
    m.map_from_base = msg::to_msg(map_from_base);
    m.map_from_odom = msg::to_msg(Pose2());
    m.covariance[0] = m.covariance[4] = 0.01;
    m.covariance[8] = 0.001;
    ASSERT_TRUE(bus::publish(*fake.bus, "SLAM_POSE", m));
  }

  // The gateway detector sees a door in the north wall, crossing point map (2, 3), tracked over
  // five scans; its points in the base frame of the robot's pose.
  void door_sighting()
  {
    const Pose2 base_from_map = robot.inverse();
    gateway_hypothesis_t h{};
    h.track_id = 4;
    h.gateway_class = gateway_hypothesis_t::CLASS_DOOR;
    for (float& p : h.class_probability) p = 0;
    h.class_probability[gateway_hypothesis_t::CLASS_DOOR] = 1;
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(1.5, 3.0), Eigen::Vector2d(2.5, 3.0)})
      h.gateway_points.push_back(msg::to_point_msg(base_from_map * p));
    h.npoints = 2;
    h.crossing_points.push_back(msg::to_point_msg(base_from_map * Eigen::Vector2d(2.0, 3.0)));
    h.ncrossing_points = 1;
    h.traversal_directions = {geometry::normalize_angle(M_PI / 2 - robot.theta()),
                              geometry::normalize_angle(-M_PI / 2 - robot.theta())};
    h.ndirections = 2;
    h.distance = 1.8f;
    h.observations = 5;
    gateway_hypotheses_t m{};
    m.utime = t;
    m.scan_id = t / 1000;
    m.map_from_base = msg::to_msg(robot);
    m.hypotheses.push_back(h);
    m.nhypotheses = 1;
    ASSERT_TRUE(bus::publish(*fake.bus, "GATEWAY_HYPOTHESES", m));
  }

  void path(int64_t goal_id, int8_t status, const std::string& reason = "")
  {
    global_path_t m{};
    m.utime = t;
    m.goal_id = goal_id;
    m.map_version = 1;
    m.cost = 0;
    m.status = status;
    m.reason = reason;
    ASSERT_TRUE(bus::publish(*fake.bus, "GLOBAL_PATH", m));
  }

  void advance(double s)
  {
    t += static_cast<int64_t>(s * 1e6);
    slam_pose(robot);
  }

  std::vector<nav_goal_t> goals() const { return testing::decoded<nav_goal_t>(*fake.bus, "NAV_GOAL"); }
  std::vector<region_name_request_t> requests() const
  {
    return testing::decoded<region_name_request_t>(*fake.bus, "REGION_NAME_REQUEST");
  }
  explorer_status_t status()
  {
    node->publish_status();
    return testing::decoded<explorer_status_t>(*fake.bus, "EXPLORER_STATUS").back();
  }
  int64_t drops_on(const std::string& channel) const { return fake.node->drops().on_channel(channel); }
};

TEST(ExplorerNode, AGoalForThePlannerOnceMapAndPoseAreThere)
{
  Fixture f;
  f.node->step();
  EXPECT_TRUE(f.goals().empty());   // nothing heard yet
  f.map(test_maps::one_room(false));
  f.node->step();
  EXPECT_TRUE(f.goals().empty());   // no pose yet
  EXPECT_EQ(f.status().phase, explorer_status_t::PHASE_WAITING);
  f.slam_pose(Pose2(1.0, 1.5, 0.0));
  f.node->step();
  const auto goals = f.goals();
  ASSERT_EQ(goals.size(), 1u);
  const nav_goal_t& g = goals[0];
  EXPECT_GT(g.goal_id, 0);
  EXPECT_FALSE(g.cancel);
  EXPECT_EQ(g.region_id, 1);
  EXPECT_TRUE(g.has_pose);
  EXPECT_DOUBLE_EQ(g.heading_tolerance, ExplorerOptions{}.view.heading_tolerance);
  EXPECT_DOUBLE_EQ(g.position_tolerance, ExplorerOptions{}.goal_tolerance);
  // The open east side is the frontier: the goal is a place in view of it, facing it.
  EXPECT_NEAR(g.region_from_goal.x, 3.3, 0.4);
  EXPECT_LT(std::abs(g.region_from_goal.theta), 0.5);
  EXPECT_GT(g.region_from_goal.y, 0.0);
  EXPECT_LT(g.region_from_goal.y, 3.0);
  const auto s = f.status();
  EXPECT_EQ(s.phase, explorer_status_t::PHASE_EXPLORING);
  EXPECT_EQ(s.goal_id, g.goal_id);
  EXPECT_EQ(s.goal_region, 1);
  EXPECT_EQ(s.goals_sent, 1);
  EXPECT_EQ(s.current_region, 1);
  EXPECT_LT(s.current_completeness, 1.0);
  // Stepping again sends nothing new while the planner pursues it.
  f.advance(0.5);
  f.path(g.goal_id, global_path_t::STATUS_OK);
  f.node->step();
  EXPECT_EQ(f.goals().size(), 1u);
}

// With the shipped config the robot first looks behind (what it saw lies ahead of it): a goal
// where it stands that asks for the heading behind it; the planner's REACHED ends it and the
// frontier comes next.
TEST(ExplorerNode, TheFirstGoalIsALookBehind)
{
  Fixture f(shipped_config());
  f.map(test_maps::one_room(false));
  f.slam_pose(Pose2(1.0, 1.5, 0.3));
  f.node->step();
  auto goals = f.goals();
  ASSERT_EQ(goals.size(), 1u);
  EXPECT_NEAR(goals[0].region_from_goal.x, 1.0, 1e-6);
  EXPECT_NEAR(goals[0].region_from_goal.y, 1.5, 1e-6);
  EXPECT_NEAR(std::abs(geometry::normalize_angle(goals[0].region_from_goal.theta - 0.3)), M_PI, 1e-6);
  EXPECT_LT(goals[0].heading_tolerance, 0.5);
  f.advance(3.0);
  f.path(goals[0].goal_id, global_path_t::STATUS_GOAL_REACHED);
  f.node->step();
  goals = f.goals();
  ASSERT_EQ(goals.size(), 2u);
  EXPECT_LT(goals[1].heading_tolerance, M_PI);
  EXPECT_NEAR(goals[1].region_from_goal.x, 3.3, 0.4) << "in view of the frontier";
}

TEST(ExplorerNode, NoPathLeadsToTheNextGoalAndAnUnreachableDoorIsSetAside)
{
  Fixture f;
  f.map(test_maps::one_room(false, 1, true));
  f.slam_pose(Pose2(1.0, 1.5, 0.0));
  f.door_sighting();
  f.node->step();
  ASSERT_EQ(f.goals().size(), 1u);
  const nav_goal_t frontier = f.goals().back();
  EXPECT_FALSE(frontier.beyond_known);
  f.advance(0.5);
  f.path(frontier.goal_id, global_path_t::STATUS_NO_PATH, "no way to the goal");
  f.node->step();
  ASSERT_EQ(f.goals().size(), 2u);
  const nav_goal_t door = f.goals().back();
  EXPECT_GT(door.goal_id, frontier.goal_id);
  EXPECT_TRUE(door.beyond_known);   // beyond the door lies unknown space
  EXPECT_GT(door.region_from_goal.y, 3.0);
  EXPECT_NEAR(door.region_from_goal.x, 2.0, 0.3);
  EXPECT_EQ(f.status().stack_pending, 1);
  f.advance(0.5);
  f.path(door.goal_id, global_path_t::STATUS_NO_PATH, "gateway closed");
  f.node->step();
  const auto s = f.status();
  EXPECT_EQ(s.stack_set_aside, 1);
  EXPECT_EQ(s.goals_failed, 2);
  EXPECT_EQ(s.goals_sent, static_cast<int>(f.goals().size()));
  // Nothing is left to try now, but the set-aside door and the failed frontier are retried
  // later: the explorer is not done.
  EXPECT_NE(s.phase, explorer_status_t::PHASE_DONE);
}

TEST(ExplorerNode, StateFileCarriesTheStackAcrossARestart)
{
  testing::TempDir dir("explorer_node");
  const ExplorerFiles files{dir.file("state/explorer.json")};
  nlohmann::json stack;
  int64_t last_goal = 0;
  {
    Fixture f(files);
    f.map(test_maps::one_room(false, 1, true));
    f.slam_pose(Pose2(1.0, 1.5, 0.0));
    f.door_sighting();
    f.node->step();
    ASSERT_EQ(f.goals().size(), 1u);
    last_goal = f.goals().back().goal_id;
    // Saved at once on a new goal: a kill now would not lose the stack.
    const auto saved = load_explorer_state(files.state_file);
    ASSERT_TRUE(saved.has_value());
    stack = f.node->explorer().stack().to_json();
    EXPECT_EQ(saved->explorer.at("stack"), stack);
    EXPECT_EQ(f.node->explorer().stack().count(StackEntry::State::kPending), 1);
  }
  Fixture g(files);
  EXPECT_TRUE(g.node->restored());
  EXPECT_EQ(g.node->explorer().stack().to_json(), stack);
  g.t = kT0 + 1'000'000;
  g.map(test_maps::one_room(false, 2, true));
  g.slam_pose(Pose2(1.0, 1.5, 0.0));
  g.node->step();
  ASSERT_FALSE(g.goals().empty()) << g.status().activity;
  // Goal ids go on where they were: the planner never takes a new goal for an old one.
  EXPECT_GT(g.goals().back().goal_id, last_goal);
  EXPECT_EQ(g.status().stack_pending, 1);

  // A damaged file is set aside; the explorer starts from scratch and writes a good one on exit.
  g.node.reset();
  std::ofstream(files.state_file) << "garbage";
  {
    Fixture h(files);
    EXPECT_FALSE(h.node->restored());
    EXPECT_TRUE(std::ifstream(files.state_file + ".damaged").good());
  }
  EXPECT_TRUE(load_explorer_state(files.state_file).has_value());
}

TEST(ExplorerNode, AClosedRoomIsDoneAndAskedToBeNamed)
{
  Fixture f;
  f.map(test_maps::one_room(true));
  f.slam_pose(Pose2(1.0, 1.5, 0.0));
  f.node->step();
  EXPECT_TRUE(f.goals().empty());
  const auto s = f.status();
  EXPECT_EQ(s.phase, explorer_status_t::PHASE_DONE) << s.activity;
  EXPECT_EQ(s.regions, 1);
  EXPECT_EQ(s.complete_regions, 1);
  const auto requests = f.requests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].region_id, 1);
  EXPECT_NEAR(requests[0].centroid.x, 2.0, 0.05);
  EXPECT_NEAR(requests[0].centroid.y, 1.5, 0.05);
  EXPECT_NEAR(requests[0].area, 12.0, 0.1);
  EXPECT_EQ(requests[0].description, "room 12 m^2 with 0 gateways");
  // Asked once, not on every step; once the map holds a name nobody asks again.
  f.node->step();
  EXPECT_EQ(f.requests().size(), 1u);
  auto named = test_maps::one_room(true, 2);
  named.region(1)->name = "kitchen";
  f.map(named);
  f.node->step();
  EXPECT_EQ(f.requests().size(), 1u);
}

TEST(ExplorerNode, MalformedAndHostileInputIsDroppedAndCounted)
{
  Fixture f;
  f.map(test_maps::one_room(false));
  f.slam_pose(Pose2(1.0, 1.5, 0.0));
  const auto raw = [&](const std::string& channel, const auto& m) {
    std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
    ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
    ASSERT_TRUE(f.fake.bus->publish(channel, buf.data(), buf.size()));
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // SLAM_POSE: NaN (wire check), 20 km away, a negative stamp, a stamp 100 s ahead.
  slam_pose_t p{};
  p.utime = f.t;
  p.map_from_base.x = nan;
  raw("SLAM_POSE", p);
  p.map_from_base.x = 2e4;
  raw("SLAM_POSE", p);
  p.map_from_base.x = 1.0;
  p.utime = -5;
  raw("SLAM_POSE", p);
  p.utime = f.t + 100'000'000;
  raw("SLAM_POSE", p);
  EXPECT_EQ(f.drops_on("SLAM_POSE"), 4);
  EXPECT_EQ(f.node->robot_utime(), f.t);
  // POSE: infinity in its map pose.
  region_pose_t rp{};
  rp.utime = f.t;
  rp.region_id = 1;
  rp.confidence = 0.9f;
  rp.map_from_base.theta = std::numeric_limits<double>::infinity();
  raw("POSE", rp);
  // GATEWAY_HYPOTHESES: a count that disagrees with its array (wire), a point 50 km away, an
  // unknown class (enum check).
  gateway_hypotheses_t gh{};
  gh.utime = f.t;
  gh.map_from_base = msg::to_msg(Pose2(1.0, 1.5, 0.0));
  gateway_hypothesis_t h{};
  h.gateway_class = gateway_hypothesis_t::CLASS_DOOR;
  h.class_probability[1] = 1;
  h.crossing_points.push_back(msg::to_point_msg(Eigen::Vector2d(5e4, 0)));
  h.ncrossing_points = 1;
  h.observations = 5;
  gh.hypotheses.push_back(h);
  gh.nhypotheses = 1;
  raw("GATEWAY_HYPOTHESES", gh);
  gh.hypotheses[0].gateway_class = 99;
  raw("GATEWAY_HYPOTHESES", gh);
  const uint8_t garbage[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  f.fake.bus->publish("GATEWAY_HYPOTHESES", garbage, sizeof garbage);
  EXPECT_EQ(f.drops_on("GATEWAY_HYPOTHESES"), 3);
  // GLOBAL_PATH: an unknown status; RG_MAP: garbage, and a map whose gateway leads nowhere.
  global_path_t gp{};
  gp.utime = f.t;
  gp.goal_id = 1;
  gp.status = 42;
  raw("GLOBAL_PATH", gp);
  f.fake.bus->publish("RG_MAP", garbage, sizeof garbage);
  auto broken = test_maps::one_room(false, 2);
  auto& gw = broken.add_gateway(rgmap::GatewayClass::kDoor, 1, kT0);
  gw.gateway_points = {{1.5, 3.0}, {2.5, 3.0}};
  gw.crossing_points = {{2.0, 3.0}};
  gw.traversal_directions = {M_PI / 2};
  rg_map_t broken_msg = rgmap::to_msg(broken);
  broken_msg.gateways[0].region_b = 77;
  ASSERT_TRUE(bus::publish(*f.fake.bus, "RG_MAP", broken_msg));
  EXPECT_EQ(f.drops_on("POSE"), 1);
  EXPECT_EQ(f.drops_on("GLOBAL_PATH"), 1);
  EXPECT_EQ(f.drops_on("RG_MAP"), 2);
  EXPECT_EQ(f.fake.node->drops().total(), 11);
  // None of it changed what the explorer holds; it explores as before.
  EXPECT_EQ(f.node->explorer().stack().entries().size(), 0u);
  f.node->step();
  ASSERT_EQ(f.goals().size(), 1u);
  EXPECT_NEAR(f.goals()[0].region_from_goal.x, 3.3, 0.4);
  f.fake.node->publish_heartbeat();
  EXPECT_EQ(testing::decoded<heartbeat_t>(*f.fake.bus, "HEARTBEAT").back().messages_dropped, 11);
}

TEST(ExplorerProcess, ShippedConfigPassesCheckConfigAndExitsCleanlyOnSigterm)
{
  using namespace std::chrono_literals;
  testing::TempDir dir("explorer_process");
  testing::ChildOptions o;
  o.stderr_path = dir.file("stderr");
  const auto check = testing::run_to_completion(
      {RGNAV_EXPLORER_BIN, "--config", RGNAV_SOURCE_DIR "/config/explorer.yaml", "--check-config"}, 30s, o);
  EXPECT_TRUE(check.clean()) << check.describe() << testing::read_file(dir.file("stderr"));
  testing::ChildProcess p({RGNAV_EXPLORER_BIN, "--config", RGNAV_SOURCE_DIR "/config/explorer.yaml", "--lcm-url",
                                    "memq://", "--state-file", dir.file("state/explorer.json")},
                                   o);
  std::this_thread::sleep_for(300ms);
  ASSERT_TRUE(p.running()) << testing::read_file(dir.file("stderr"));
  ASSERT_TRUE(p.signal(SIGTERM));
  const auto status = p.wait_for(10s);
  ASSERT_TRUE(status.has_value()) << "still running 10 s after SIGTERM";
  EXPECT_TRUE(status->clean()) << status->describe() << "\n" << testing::read_file(dir.file("stderr"));
  // Stopping saved the (empty) state.
  EXPECT_TRUE(load_explorer_state(dir.file("state/explorer.json")).has_value());
}

}  // namespace
}  // namespace rgnav::explorer
