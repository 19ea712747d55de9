#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "bad_files.h"
#include "fake_bus_node.h"
#include "laser_scan_msg.h"
#include "procs/tour_runner/pure_pursuit.h"
#include "procs/tour_runner/tour.h"
#include "procs/tour_runner/tour_runner_node.h"
#include "procs/tour_runner/tour_sequencer.h"
#include "rgnav/slam_pose_t.hpp"
#include "rgnav/target_list_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"

namespace rgnav::tour_runner {
namespace {

using Eigen::Vector2d;

std::string write_tour(const std::string& text)
{
  const std::string path = ::testing::TempDir() + "/tour_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml";
  std::ofstream(path) << text;
  return path;
}

// Issue 35: a tour file of random bytes, an empty one and one cut off inside its list of points
// are refused naming the file.
TEST(Tour, RandomBytesEmptyAndCutOffFilesAreRefusedNamingThem)
{
  testing::TempDir dir("tour_bad");
  const std::string valid = "# tour\nstart: [1, 2, 0.5]\ntour: [[3, 4], [5, 6], [7, 8]]\n";
  for (const auto& f : testing::write_bad_files(dir.path(), "tour.yaml", valid, valid.find("[5") + 2)) {
    SCOPED_TRACE(f.kind);
    try {
      load_tour(f.path);
      ADD_FAILURE() << f.path << " was loaded";
    } catch (const config::ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(f.path + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(Tour, DensifyKeepsSpacingAndEndpoints)
{
  const auto pts = densify({Vector2d(4, 0), Vector2d(4, 1)}, Vector2d(0, 0), 1.5);
  ASSERT_EQ(pts.size(), 4u);  // 4 m in 3 pieces, then 1 m in 1
  EXPECT_TRUE(pts[2].isApprox(Vector2d(4, 0)));
  EXPECT_TRUE(pts.back().isApprox(Vector2d(4, 1)));
  Vector2d prev(0, 0);
  for (const auto& p : pts) {
    EXPECT_LE((p - prev).norm(), 1.5 + 1e-9);
    prev = p;
  }
}

TEST(Tour, LoadsStartAndPointsAndRefusesBadOnes)
{
  const auto t = load_tour(write_tour("start: [1, 2, 0.5]\nwalls: []\ntour: [[3, 4], [5, 6]]\n"));
  EXPECT_DOUBLE_EQ(t.world_from_start.x(), 1);
  EXPECT_DOUBLE_EQ(t.world_from_start.theta(), 0.5);
  ASSERT_EQ(t.world_points.size(), 2u);
  EXPECT_TRUE(t.world_points[1].isApprox(Vector2d(5, 6)));
  try {
    load_tour(write_tour("tour: [[1, 2], [3]]\n"));
    FAIL() << "accepted a point with one coordinate";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tour[1]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_tour(write_tour("start: [0, 0, 0]\n")), config::ConfigError);
  const auto flat = load_tour(write_tour("start: [0, 0, 0]\ntour: [1, 2, 3, 4, 5, 6]\n"));
  ASSERT_EQ(flat.world_points.size(), 3u);
  EXPECT_TRUE(flat.world_points[2].isApprox(Vector2d(5, 6)));
  EXPECT_THROW(load_tour(write_tour("tour: [1, 2, 3]\n")), config::ConfigError);
}

TEST(TourSequencer, AdvancesAndSkipsCutCorners)
{
  TourSequencer s({0.3, 3}, {Vector2d(1, 0), Vector2d(2, 0), Vector2d(3, 0)});
  EXPECT_FALSE(s.update(geometry::Pose2(0, 0, 0)));
  EXPECT_EQ(s.upcoming().size(), 3u);
  EXPECT_EQ(s.goal_id(), 1);
  EXPECT_TRUE(s.update(geometry::Pose2(1.9, 0.1, 0)));  // target 2 reached first: 1 skipped
  EXPECT_EQ(s.reached(), 2u);
  EXPECT_EQ(s.goal_id(), 3);  // a new goal: collision avoidance decides anew
  EXPECT_TRUE(s.update(geometry::Pose2(3, 0, 0)));
  EXPECT_TRUE(s.done());
  EXPECT_TRUE(s.upcoming().empty());
}

TEST(PurePursuit, TurnsInPlaceForTargetBehind)
{
  const auto c = pursue({}, geometry::Pose2(0, 0, 0), Vector2d(-2, 0.1), {});
  EXPECT_EQ(c.v, 0);
  EXPECT_NE(c.omega, 0);
}

TEST(PurePursuit, StopsForObstacleAheadAndSteersTowardTarget)
{
  PursuitOptions o;
  const auto free = pursue(o, geometry::Pose2(0, 0, 0), Vector2d(2, 0.5), {});
  EXPECT_GT(free.v, 0);
  EXPECT_GT(free.omega, 0);  // target to the left
  const auto blocked = pursue(o, geometry::Pose2(0, 0, 0), Vector2d(2, 0), {Vector2d(0.35, 0.0)});
  EXPECT_TRUE(blocked.blocked);
  EXPECT_EQ(blocked.v, 0);
  // An obstacle beside the corridor does not stop the robot.
  EXPECT_FALSE(pursue(o, geometry::Pose2(0, 0, 0), Vector2d(2, 0), {Vector2d(0.4, 1.0)}).blocked);
  // Blocked with free space to the left: it turns left in place.
  std::vector<Vector2d> wall_right;
  for (double y = -1.5; y <= 0.2; y += 0.05) wall_right.emplace_back(0.35, y);
  const auto turn = pursue(o, geometry::Pose2(0, 0, 0), Vector2d(2, 0), wall_right);
  EXPECT_TRUE(turn.blocked);
  EXPECT_EQ(turn.v, 0);
  EXPECT_GT(turn.omega, 0);
  ASSERT_TRUE(std::isfinite(turn.escape_heading));
  EXPECT_GT(turn.escape_heading, 0);
  // Escaping: first turn to the committed heading, then creep along it while it is free.
  const auto rotate = escape(o, turn.escape_heading, wall_right);
  EXPECT_EQ(rotate.v, 0);
  EXPECT_GT(rotate.omega, 0);
  std::vector<Vector2d> wall_ahead_right;
  for (double y = -1.5; y <= -0.4; y += 0.05) wall_ahead_right.emplace_back(0.35, y);
  const auto creep = escape(o, 0.05, wall_ahead_right);
  EXPECT_GT(creep.v, 0);
  EXPECT_TRUE(escape(o, 0.0, wall_right).blocked);
}

struct NodeHarness : rgnav::testing::FakeBusNode
{
  explicit NodeHarness(TourRunnerOptions::Output output) : FakeBusNode("tour_runner")
  {
    TourRunnerOptions o;
    o.tour_file = write_tour("start: [10, 0, 1.5707963267948966]\ntour: [[10, 2]]\n");
    o.output = output;
    o.max_spacing = 1.0;
    runner = std::make_unique<TourRunnerNode>(*node, o, Channels{});
  }
  void odometry(int64_t utime, double x, double y, double th, int64_t seq)
  {
    odometry_t m{};
    m.utime = utime;
    m.seq = seq;
    m.odom_from_base.x = x;
    m.odom_from_base.y = y;
    m.odom_from_base.theta = th;
    m.status = odometry_t::STATUS_OK;
    bus::publish(*bus, "ODOMETRY", m);
  }
  void scan(int64_t utime)
  {
    bus::publish(*bus, "LASER_FRONT", rgnav::testing::laser_scan_msg(utime, utime, 8.183f, 8.183f));
  }
  template <class T>
  std::vector<T> received(const std::string& ch)
  {
    return rgnav::testing::decoded<T>(*bus, ch);
  }
  std::unique_ptr<TourRunnerNode> runner;
};

TEST(TourRunnerNode, TargetsAreInTheOdomFrameAndRunEnds)
{
  NodeHarness h(TourRunnerOptions::Output::kTargets);
  // World start (10, 0) facing +y; the waypoint (10, 2) is 2 m straight ahead: odom (2, 0).
  h.odometry(1'000'000, 0, 0, 0, 0);
  auto targets = h.received<target_list_t>("TARGETS");
  ASSERT_FALSE(targets.empty());
  ASSERT_EQ(targets.back().ntargets, 2);
  EXPECT_NEAR(targets.back().odom_from_target[0].x, 1.0, 1e-9);
  EXPECT_NEAR(targets.back().odom_from_target[1].x, 2.0, 1e-9);
  EXPECT_NEAR(targets.back().odom_from_target[1].y, 0.0, 1e-9);
  EXPECT_TRUE(targets.back().final_is_goal);
  EXPECT_EQ(targets.back().goal_id, 1);  // names the target driven to (re-sends keep it)
  h.odometry(2'000'000, 1.0, 0, 0, 1);
  h.odometry(3'000'000, 2.0, 0, 0, 2);
  EXPECT_TRUE(h.node->stop_requested());
}

TEST(TourRunnerNode, SlamCorrectionMovesTargetsIntoTheDriftedOdomFrame)
{
  NodeHarness h(TourRunnerOptions::Output::kTargets);
  // Odometry has drifted: the map (start) frame point p is at odom point p + (0, 0.5), i.e.
  // map_from_odom translates by (0, -0.5).
  slam_pose_t s{};
  s.utime = 1'000'000;
  s.scan_id = 1;
  s.map_from_odom.y = -0.5;
  s.covariance[0] = s.covariance[4] = s.covariance[8] = 1e-4;
  bus::publish(*h.bus, "SLAM_POSE", s);
  // The robot at odom (0, 0.5) is at the start in the map: the first target is 1 m ahead.
  h.odometry(1'000'000, 0, 0.5, 0, 0);
  auto targets = h.received<target_list_t>("TARGETS");
  ASSERT_FALSE(targets.empty());
  EXPECT_NEAR(targets.back().odom_from_target[0].x, 1.0, 1e-9);
  EXPECT_NEAR(targets.back().odom_from_target[0].y, 0.5, 1e-9);
  // Reaching is judged in the map frame: odom (2, 0) is map (2, -0.5), not the goal.
  h.odometry(2'000'000, 1.0, 0.5, 0, 1);
  h.odometry(3'000'000, 2.0, 0.0, 0, 2);
  EXPECT_FALSE(h.node->stop_requested());
  h.odometry(4'000'000, 2.0, 0.5, 0, 3);
  EXPECT_TRUE(h.node->stop_requested());
}

TEST(TourRunnerNode, FollowerHoldsStillWithoutScansThenDrives)
{
  NodeHarness h(TourRunnerOptions::Output::kBaseCmd);
  h.odometry(1'000'000, 0, 0, 0, 0);
  auto cmds = h.received<velocity_cmd_t>("BASE_CMD");
  ASSERT_EQ(cmds.size(), 1u);
  EXPECT_EQ(cmds[0].v, 0);  // no scan yet: fail safe
  h.scan(1'010'000);
  h.odometry(1'020'000, 0, 0, 0, 1);
  cmds = h.received<velocity_cmd_t>("BASE_CMD");
  ASSERT_EQ(cmds.size(), 2u);
  EXPECT_GT(cmds[1].v, 0);
  EXPECT_GT(cmds[1].deadline_us, 0);
  // The scan goes stale in message time: the follower stops again.
  h.odometry(3'000'000, 0.1, 0, 0, 2);
  EXPECT_EQ(h.received<velocity_cmd_t>("BASE_CMD").back().v, 0);
}

}  // namespace
}  // namespace rgnav::tour_runner
