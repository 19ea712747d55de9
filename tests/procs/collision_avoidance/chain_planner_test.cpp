#include "collision_avoidance/chain_planner.h"

#include <gtest/gtest.h>

#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

// A corridor along +x (walls at y = +-1.5) with the given extra obstacles, scanned from the origin.
LocalMap corridor(const std::vector<testing::Wall>& extra)
{
  std::vector<testing::Wall> walls = {{{-1, -1.5}, {12, -1.5}}, {{-1, 1.5}, {12, 1.5}}};
  walls.insert(walls.end(), extra.begin(), extra.end());
  LocalMap map(LocalMapOptions{});
  ScanPoints s;
  s.stamp = time::from_utime(1'000'000);
  for (const auto& r : testing::cast(Pose2(), walls))
    if (r.range < 8.0) s.points.emplace_back(r.range * std::cos(r.bearing), r.range * std::sin(r.bearing));
  map.add_scan(s);
  map.rebuild(s.stamp);
  return map;
}

TEST(ChainPlanner, StraightWhenFree)
{
  const LocalMap map = corridor({});
  ChainPlanner p(PlannerOptions{});
  const auto c = p.plan(Pose2(), 0.0, {Pose2(2.0, 0.0, 0.0)}, map, 0.5);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->chain.length(), 2.0, 1e-6);
  EXPECT_GT(c->predicted_time, 2.0 / 0.5);
}

TEST(ChainPlanner, DetoursAroundABox)
{
  const LocalMap map = corridor(testing::box(1.2, -0.3, 1.6, 0.3));
  PlannerOptions o;
  ChainPlanner p(o);
  const Pose2 goal(3.0, 0.0, 0.0);
  const auto c = p.plan(Pose2(), 0.0, {goal}, map, 0.5);
  ASSERT_TRUE(c);
  EXPECT_GT(c->chain.length(), 3.0);  // not the straight line
  EXPECT_FALSE(first_collision(c->chain, map, o.robot_radius + o.safety_margin, 0.01));
  EXPECT_NEAR((c->chain.end().translation() - goal.translation()).norm(), 0.0, 1e-6);
  EXPECT_GE(c->min_clearance, o.robot_radius + o.safety_margin);
}

TEST(ChainPlanner, NothingWhenTheCorridorIsClosed)
{
  const LocalMap map = corridor({{{1.5, -1.5}, {1.5, 1.5}}});
  ChainPlanner p(PlannerOptions{});
  EXPECT_FALSE(p.plan(Pose2(), 0.0, {Pose2(3.0, 0.0, 0.0)}, map, 0.5));
}

TEST(ChainPlanner, TurnsInPlaceForTargetsBehind)
{
  const LocalMap map = corridor({});
  ChainPlanner p(PlannerOptions{});
  const auto c = p.plan(Pose2(2.0, 0.0, 0.0), 0.0, {Pose2(0.5, 0.0, M_PI)}, map, 0.5);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->chain[0].kind(), trajectory::Kind::kTurn);
}

// A hallway 0.9 m wide, the robot 0.12 m off its centre line: 0.33 m from one wall, a few
// centimetres short of its clearance (0.36 m). A chain back to the centre line gains that only
// slowly at first; it must still be taken (the robot stood turning on the spot in there), while
// one that runs on along the wall without making up the clearance is not.
TEST(ChainPlanner, LeavesAWallItIsNearlyClearOfAlongTheHallway)
{
  const std::vector<testing::Wall> walls = {{{-1, -0.33}, {6, -0.33}}, {{-1, 0.57}, {6, 0.57}}};
  LocalMap map(LocalMapOptions{});
  // Seen for over a second: static walls (what was just seen keeps the margin from what moves).
  for (int64_t us = 1'000'000; us <= 2'200'000; us += 100'000) {
    const ScanPoints s = testing::scan_points(Pose2(), walls, time::from_utime(us), map.max_range());
    map.add_scan(s);
    map.rebuild(s.stamp);
  }
  ASSERT_EQ(map.moving_size(), 0u);
  PlannerOptions o;
  const double clearance = o.robot_radius + o.safety_margin;
  ASSERT_LT(map.clearance(Eigen::Vector2d::Zero(), clearance), clearance - 0.02);
  ChainPlanner p(o);
  const auto c = p.plan(Pose2(), 0.0, {Pose2(1.5, 0.12, 0.0), Pose2(2.5, 0.12, 0.0)}, map, 0.5);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->chain.end().translation().y(), 0.12, 1e-6);
  const trajectory::Chain along({trajectory::Segment::line(Pose2(), 2.0)});
  EXPECT_TRUE(first_collision(along, map, clearance, o.check_step));
}

}  // namespace
}  // namespace rgnav::collision_avoidance
