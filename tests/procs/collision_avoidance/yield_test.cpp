// Giving way sideways (give_way.h): the yield point lies out of the person's predicted path
// beside a doorway or beyond a hallway's mouth, never back along their path (as the old give-way
// line did: the failure it fixes); and waiting there lasts until nobody is left to pass.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_avoidance/chain_planner.h"
#include "collision_avoidance/give_way.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

using testing::Wall;
constexpr double kClearance = 0.36;  // robot radius + safety margin

// The local map after scans from `at` facing each of `headings` (the laser looks ahead only).
LocalMap seen_from(const Eigen::Vector2d& at, const std::vector<double>& headings, const std::vector<Wall>& walls)
{
  LocalMap map(LocalMapOptions{});
  int64_t us = 1'000'000;
  for (const double h : headings) {
    us += 100'000;
    map.add_scan(testing::scan_points(Pose2(at, h), walls, time::from_utime(us), map.max_range()));
  }
  map.rebuild(time::from_utime(us));
  return map;
}

// A wall across x = 1 with a doorway 0.9 m wide at y = 0; a person (a 0.4 m box) in it.
std::vector<Wall> doorway_with_person()
{
  std::vector<Wall> w = {{{1.0, -3.0}, {1.0, -0.45}}, {{1.0, 0.45}, {1.0, 3.0}}};
  for (const auto& side : testing::box(1.1, -0.2, 1.5, 0.2)) w.push_back(side);
  return w;
}

// Turns on the spot and straight legs through the corners (how the robot drives there).
trajectory::Chain polyline(Pose2 from, const std::vector<Eigen::Vector2d>& corners)
{
  trajectory::Chain c;
  for (const auto& p : corners) {
    const Eigen::Vector2d d = p - from.translation();
    const double dth = geometry::normalize_angle(std::atan2(d.y(), d.x()) - from.theta());
    if (std::fabs(dth) > 1e-3) {
      c.push_back(trajectory::Segment::turn(from, dth));
      from = c.end();
    }
    c.push_back(trajectory::Segment::line(from, d.norm()));
    from = c.end();
  }
  return c;
}

TEST(YieldPoint, SidewaysBesideADoorwayNotBackAlongThePersonsPath)
{
  const Eigen::Vector2d robot(0.0, 0.0);
  const LocalMap map = seen_from(robot, {0.0, M_PI}, doorway_with_person());
  PersonPath path;
  path.from = {1.3, 0.0};
  path.direction = {-1.0, 0.0};  // coming through the door, at the robot
  const YieldOptions o;
  const auto y = choose_yield_point(map, robot, path, kClearance, o);
  ASSERT_TRUE(y.has_value());
  const double off_needed = kClearance + o.path_half_width + o.extra;
  EXPECT_GE(y->off_path, off_needed - 1e-9);
  EXPECT_GE(std::fabs(y->point.y()), off_needed - 1e-9) << "out of the path sideways";
  EXPECT_LT(path.along(y->point) - path.along(robot), 1.0) << "not far back down the person's path";
  EXPECT_LT(y->travel, 2.5);
  ASSERT_FALSE(y->corners.empty());
  EXPECT_NEAR((y->corners.back() - y->point).norm(), 0.0, 1e-9);
  EXPECT_FALSE(first_collision(polyline(Pose2(robot, 0.0), y->corners), map, kClearance, 0.05).has_value());

  // The old give-way, for comparison: straight back, away from the target, which is the
  // person's path; its whole line stays in it (they walk up again and wait again).
  const auto old = choose_give_way(map, robot, M_PI, kClearance, 0.05, GiveWayOptions{});
  ASSERT_TRUE(old.has_value());
  const Eigen::Vector2d end = robot + old->length * Eigen::Vector2d(std::cos(old->heading), std::sin(old->heading));
  EXPECT_LT(path.distance(end), kClearance + o.path_half_width);
}

TEST(YieldPoint, BeyondTheMouthOfAHallwayOnceTheRobotLookedBehind)
{
  // A hallway 1.1 m wide along x over [-3, 3], the robot in it, a person ahead coming its way;
  // behind the robot, past the mouth, a room (its wall along x = -3).
  std::vector<Wall> w = {{{-3.0, -0.55}, {3.0, -0.55}}, {{-3.0, 0.55}, {3.0, 0.55}},
                         {{-3.0, 0.55}, {-3.0, 4.0}},   {{-3.0, -0.55}, {-3.0, -4.0}}};
  for (const auto& side : testing::box(0.0, -0.2, 0.4, 0.2)) w.push_back(side);
  PersonPath path;
  path.from = {0.2, 0.0};
  path.direction = {-1.0, 0.0};
  const YieldOptions o;
  const double off_needed = kClearance + o.path_half_width + o.extra;
  for (const double x : {-1.0, -2.4}) {
    const Eigen::Vector2d robot(x, 0.0);
    // Facing the person only: nothing known behind, no place out of the way.
    EXPECT_FALSE(choose_yield_point(seen_from(robot, {0.0}, w), robot, path, kClearance, o).has_value()) << x;
    // Having turned to look: out of the hallway and aside (from deep in it, the room is seen
    // through the mouth only: farther out), off the person's line however far they walk on.
    const LocalMap map = seen_from(robot, {0.0, M_PI}, w);
    const auto y = choose_yield_point(map, robot, path, kClearance, o);
    ASSERT_TRUE(y.has_value()) << x;
    EXPECT_LT(y->point.x(), -3.0 - kClearance) << x;
    EXPECT_GE(std::fabs(y->point.y()), off_needed - 1e-9) << x;
    EXPECT_LE(y->travel, o.max_travel) << x;
    EXPECT_FALSE(first_collision(polyline(Pose2(robot, M_PI), y->corners), map, kClearance, 0.05).has_value()) << x;
    // Near the mouth the room beside it is in view: the place is right beside the mouth.
    if (x < -2.0) EXPECT_GT(y->point.x(), -3.0 - kClearance - 1.0) << x;
  }
}

TEST(YieldPoint, NothingWhenBoxedIn)
{
  const Eigen::Vector2d robot(0.0, 0.0);
  const LocalMap map = seen_from(robot, {0.0, M_PI_2, M_PI, -M_PI_2}, testing::box(-0.6, -0.6, 0.6, 0.6));
  PersonPath path;
  path.from = {0.5, 0.0};
  path.direction = {-1.0, 0.0};
  EXPECT_FALSE(choose_yield_point(map, robot, path, kClearance, YieldOptions{}).has_value());
}

TEST(YieldPoint, AlreadyOutOfThePathIsWhereItWaits)
{
  const Eigen::Vector2d robot(0.0, 2.0);
  const LocalMap map = seen_from(robot, {0.0, M_PI}, {});
  PersonPath path;
  path.from = {3.0, 0.0};
  path.direction = {-1.0, 0.0};
  const auto y = choose_yield_point(map, robot, path, kClearance, YieldOptions{});
  ASSERT_TRUE(y.has_value());
  EXPECT_TRUE(y->corners.empty());
  EXPECT_DOUBLE_EQ(y->travel, 0.0);
}

// A person (0.4 m box) walking along y = 0 from x0 to x1 at 1 m/s, scanned at 10 Hz by a robot
// standing at (0, 1.4) facing `facing`; the map after the walk.
LocalMap watch_walk(double x0, double x1, double facing)
{
  LocalMap map(LocalMapOptions{});
  const Eigen::Vector2d robot(0.0, 1.4);
  const double dir = x1 > x0 ? 1.0 : -1.0;
  int64_t us = 1'000'000;
  for (double x = x0; dir * (x1 - x) >= -1e-9; x += dir * 0.1) {
    us += 100'000;
    map.add_scan(testing::scan_points(Pose2(robot, facing), testing::box(x - 0.2, -0.2, x + 0.2, 0.2),
                                      time::from_utime(us), map.max_range()));
    map.rebuild(time::from_utime(us));
  }
  return map;
}

TEST(SomeoneToPass, WhileTheyComeNotOnceTheyPassedOrTurnedBack)
{
  PersonPath path;
  path.from = {3.0, 0.0};
  path.direction = {-1.0, 0.0};
  const Eigen::Vector2d robot(0.0, 1.4);
  const YieldOptions o;
  // Coming, still on the robot's far side of it along the path.
  EXPECT_EQ(someone_to_pass(watch_walk(3.0, 1.0, 0.0), path, robot, o), ToPass::kWalking);
  // Past the robot (and walking on): nobody left to pass.
  EXPECT_EQ(someone_to_pass(watch_walk(3.0, -2.0, -M_PI_2), path, robot, o), ToPass::kNobody);
  // Turned back, walking away up the path: not coming.
  EXPECT_EQ(someone_to_pass(watch_walk(1.0, 3.0, 0.0), path, robot, o), ToPass::kNobody);
  // Nobody there at all.
  EXPECT_EQ(someone_to_pass(seen_from(robot, {0.0}, {}), path, robot, o), ToPass::kNobody);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
