// The planner node's plain parts: the message conversions (round trip of goals, the route as
// GLOBAL_PATH waypoints with the gateways marked), which pose the planner gets (the localizer's
// while fresh, carried forward by odometry within limits), and the state file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "bad_files.h"
#include "bus/typed.h"
#include "child_process.h"
#include "planner/planner_conversions.h"
#include "planner/planner_state.h"
#include "planner/pose_source.h"

namespace rgnav::planner {
namespace {

using geometry::Pose2;

TEST(PlannerConversions, GoalRoundTrip)
{
  NavGoal g;
  g.goal_id = 12;
  g.region_id = 0;
  g.region_name = "lab";
  g.has_pose = true;
  g.region_from_goal = Pose2(1.5, -2.0, 0.7);
  g.position_tolerance = 0.2;
  g.heading_tolerance = 0.1;
  const nav_goal_t m = to_msg(g, 1'700'000'000'000'000);
  std::vector<uint8_t> buf;
  std::string why;
  ASSERT_TRUE(bus::encode(m, &buf, &why)) << why;
  nav_goal_t back_msg;
  ASSERT_TRUE(bus::decode(buf.data(), buf.size(), &back_msg, &why)) << why;
  const NavGoal back = to_nav_goal(back_msg);
  EXPECT_EQ(back.goal_id, g.goal_id);
  EXPECT_EQ(back.region_id, g.region_id);
  EXPECT_EQ(back.region_name, g.region_name);
  EXPECT_EQ(back.has_pose, g.has_pose);
  EXPECT_EQ(back.region_from_goal.x(), g.region_from_goal.x());
  EXPECT_EQ(back.region_from_goal.y(), g.region_from_goal.y());
  EXPECT_EQ(back.region_from_goal.theta(), g.region_from_goal.theta());
  EXPECT_EQ(back.position_tolerance, g.position_tolerance);
  EXPECT_EQ(back.heading_tolerance, g.heading_tolerance);
  EXPECT_FALSE(back_msg.cancel);
}

TEST(PlannerConversions, RouteBecomesWaypointsWithTheGatewaysMarked)
{
  PathReport r;
  r.utime = 5;
  r.goal_id = 3;
  r.status = GoalStatus::kActive;
  r.reason = std::string(1500, 'r');
  r.remaining_s = 12.5;
  RouteLeg a;
  a.region_id = 1;
  a.exit_gateway = 4;
  a.points = {{1, 1}, {2, 1}, {2, 3}};
  RouteLeg b;
  b.region_id = 2;
  b.entry_gateway = 4;
  b.points = {{0, 0}, {1, 0}};
  r.route.legs = {a, b};
  r.route.has_goal_heading = true;
  r.route.goal_heading = -1.0;
  r.route.map_version = 9;
  const global_path_t m = to_msg(r, 9);
  std::vector<uint8_t> buf;
  std::string why;
  EXPECT_TRUE(bus::encode(m, &buf, &why)) << why;   // within the message's limits (reason cut)
  EXPECT_EQ(m.status, global_path_t::STATUS_OK);
  EXPECT_EQ(m.cost, 12.5);
  EXPECT_EQ(m.map_version, 9);
  EXPECT_EQ(m.reason.size(), 1000u);
  ASSERT_EQ(m.nwaypoints, 5);
  EXPECT_EQ(m.waypoints[0].region_id, 1);
  EXPECT_EQ(m.waypoints[0].gateway_id, 0);
  EXPECT_NEAR(m.waypoints[0].pose.theta, 0.0, 1e-12);         // toward (2, 1)
  EXPECT_NEAR(m.waypoints[1].pose.theta, M_PI / 2, 1e-12);    // toward (2, 3)
  EXPECT_EQ(m.waypoints[2].gateway_id, 4);                    // leaves room 1 through gateway 4 ...
  EXPECT_EQ(m.waypoints[3].region_id, 2);
  EXPECT_EQ(m.waypoints[3].gateway_id, 4);                    // ... and enters room 2 through it
  EXPECT_EQ(m.waypoints[4].gateway_id, 0);
  EXPECT_NEAR(m.waypoints[4].pose.theta, -1.0, 1e-12);        // the goal heading
  EXPECT_EQ(to_msg_status(GoalStatus::kNoPath), global_path_t::STATUS_NO_PATH);
  EXPECT_EQ(to_msg_status(GoalStatus::kReached), global_path_t::STATUS_GOAL_REACHED);
  EXPECT_EQ(to_msg_status(GoalStatus::kCancelled), global_path_t::STATUS_CANCELLED);
}

RobotPose fix(int64_t utime, int64_t region, const Pose2& region_from_base, const Pose2& odom_from_base)
{
  RobotPose p;
  p.utime = utime;
  p.region_id = region;
  p.region_from_base = region_from_base;
  p.odom_from_base = odom_from_base;
  return p;
}

TEST(PlannerConversions, YieldingToAPersonIsNotBlocked)
{
  // Standing aside for a person is a wait the person ends; taking it for a blocked passage sent
  // the robot round the building.
  ca_status_t m{};
  for (const int8_t mode : {ca_status_t::MODE_REACTIVE, ca_status_t::MODE_BLOCKED}) {
    m.mode = mode;
    EXPECT_TRUE(cannot_pass(m)) << int(mode);
  }
  for (const int8_t mode : {ca_status_t::MODE_IDLE, ca_status_t::MODE_PLANNED, ca_status_t::MODE_YIELDING,
                            ca_status_t::MODE_ARRIVED}) {
    m.mode = mode;
    EXPECT_FALSE(cannot_pass(m)) << int(mode);
  }
}

TEST(PoseSource, PrefersTheLocalizerWhileFreshAndCarriesFixesByOdometry)
{
  PoseSource s(PoseSourceOptions{1.0, 2.0});
  const int64_t t0 = 1'000'000'000;
  // The scan mapper alone: its fixes are used.
  ASSERT_TRUE(s.slam(fix(t0, 1, Pose2(1, 1, 0), Pose2(0, 0, 0))).has_value());
  // The localizer's fix wins, and while it is fresh the scan mapper's are not used.
  ASSERT_TRUE(s.localized(fix(t0 + 100'000, 2, Pose2(5, 5, 0), Pose2(0.1, 0, 0))).has_value());
  EXPECT_FALSE(s.slam(fix(t0 + 200'000, 1, Pose2(1.2, 1, 0), Pose2(0.2, 0, 0))).has_value());
  // Odometry carries the localizer's fix: 0.5 m further along its heading, now.
  auto p = s.odometry(t0 + 900'000, Pose2(0.6, 0, 0));
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->region_id, 2);
  EXPECT_EQ(p->utime, t0 + 900'000);
  EXPECT_NEAR(p->region_from_base.x(), 5.5, 1e-9);
  EXPECT_NEAR(p->region_from_base.y(), 5.0, 1e-9);
  EXPECT_NEAR(p->odom_from_base.x(), 0.6, 1e-12);
  // Two seconds on, the localizer's fix is stale and the scan mapper's newer: that one is carried.
  p = s.odometry(t0 + 2'200'000, Pose2(0.7, 0, 0));
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->region_id, 1);
  EXPECT_NEAR(p->region_from_base.x(), 1.7, 1e-9);
  // Carried no further than max_carry_m: beyond it the fixes have stopped coming.
  EXPECT_FALSE(s.odometry(t0 + 2'300'000, Pose2(2.5, 0, 0)).has_value());
  // Nor across an odometry restart, until the next fix.
  s.odometry_restarted();
  EXPECT_FALSE(s.odometry(t0 + 2'400'000, Pose2(0.3, 0, 0)).has_value());
  ASSERT_TRUE(s.localized(fix(t0 + 2'500'000, 2, Pose2(6, 5, 0), Pose2(0, 0, 0))).has_value());
  EXPECT_TRUE(s.odometry(t0 + 2'600'000, Pose2(0.1, 0, 0)).has_value());
  // An older fix than the one held is not taken.
  EXPECT_FALSE(s.localized(fix(t0, 2, Pose2(0, 0, 0), Pose2(0, 0, 0))).has_value());
}

TEST(PlannerState, RoundTripAndRefusal)
{
  testing::TempDir dir("planner_state");
  PlannerState s;
  s.utime = 42;
  s.costs = {{"anything", 1}};
  s.names = {{2, "lab"}, {5, "hall east"}};
  NavGoal g;
  g.goal_id = 8;
  g.region_name = "lab";
  g.region_from_goal = Pose2(1, 2, 0.5);
  s.goal = g;
  save_planner_state(dir.file("sub/state.json"), s);
  const auto back = load_planner_state(dir.file("sub/state.json"));
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->utime, 42);
  EXPECT_EQ(back->costs, s.costs);
  EXPECT_EQ(back->names, s.names);
  ASSERT_TRUE(back->goal.has_value());
  EXPECT_EQ(back->goal->goal_id, 8);
  EXPECT_EQ(back->goal->region_name, "lab");
  EXPECT_NEAR(back->goal->region_from_goal.theta(), 0.5, 1e-12);
  EXPECT_FALSE(load_planner_state(dir.file("none")).has_value());
  std::ofstream(dir.file("bad")) << "not a checkpoint";
  EXPECT_THROW(load_planner_state(dir.file("bad")), std::runtime_error);
  // A well-framed file with a bad value is refused too.
  s.names[3] = "bad\tname";
  save_planner_state(dir.file("bad_name"), s);
  EXPECT_THROW(load_planner_state(dir.file("bad_name")), std::runtime_error);
}

// Issue 35: random bytes, an empty file and one cut off mid-content are refused naming the file
// (the node then sets the file aside and starts afresh: the node tests).
TEST(PlannerState, RandomBytesEmptyAndCutOffFilesAreRefusedNamingThem)
{
  testing::TempDir dir("plannerstate_bad");
  PlannerState s;
  s.utime = 42;
  s.names = {{2, "lab"}};
  save_planner_state(dir.file("valid.json"), s);
  for (const auto& f : testing::write_bad_files(dir.path(), "planner.json", testing::read_file(dir.file("valid.json")))) {
    SCOPED_TRACE(f.kind);
    try {
      load_planner_state(f.path);
      ADD_FAILURE() << f.path << " was read";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(f.path + ": ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace rgnav::planner
