#include "collision_avoidance/grid_path.h"

#include <gtest/gtest.h>

#include "collision_avoidance/chain_planner.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

// Obstacles scanned from `laser` into a fresh local map.
LocalMap scanned(const Pose2& laser, const std::vector<testing::Wall>& walls)
{
  LocalMap map(LocalMapOptions{});
  const ScanPoints s = testing::scan_points(laser, walls, time::from_utime(1'000'000), map.max_range());
  map.add_scan(s);
  map.rebuild(s.stamp);
  return map;
}

std::vector<testing::Wall> corridor_with(std::vector<testing::Wall> extra)
{
  std::vector<testing::Wall> w = {{{-1, -1.5}, {12, -1.5}}, {{-1, 1.5}, {12, 1.5}}};
  w.insert(w.end(), extra.begin(), extra.end());
  return w;
}

constexpr double kClearance = 0.36;  // B21r radius + safety margin

void expect_legs_free(const LocalMap& map, Eigen::Vector2d from, const std::vector<Eigen::Vector2d>& corners)
{
  for (const auto& c : corners) {
    for (double t = 0.0; t <= 1.0; t += 0.02)
      EXPECT_GE(map.clearance(from + t * (c - from), kClearance), kClearance - 1e-6)
          << "leg to (" << c.transpose() << ") at t=" << t;
    from = c;
  }
}

TEST(GridPath, GoesAroundACupInFrontOfTheTarget)
{
  // A cup open away from the robot, across the corridor's middle: the straight way and every
  // single lateral via-pose end inside it.
  std::vector<testing::Wall> cup = {{{2.0, -0.5}, {2.0, 0.5}}, {{2.0, -0.5}, {1.4, -0.5}}, {{2.0, 0.5}, {1.4, 0.5}}};
  const LocalMap map = scanned(Pose2(), corridor_with(cup));
  const Eigen::Vector2d from(0, 0), to(3.5, 0);
  const auto path = grid_path(map, from, to, kClearance, GridPathOptions{});
  ASSERT_TRUE(path);
  ASSERT_GE(path->size(), 2u);  // at least one corner besides the target
  EXPECT_TRUE(path->back().isApprox(to));
  expect_legs_free(map, from, *path);
  // Around, not through: some corner lies beyond the cup's side.
  double widest = 0;
  for (const auto& c : *path) widest = std::max(widest, std::fabs(c.y()));
  EXPECT_GT(widest, 0.5 + kClearance - 0.05);
}

TEST(GridPath, NothingWhenTheWayIsShut)
{
  // Shut ahead; behind the robot nothing was seen, so no way around through there either.
  const LocalMap map = scanned(Pose2(), corridor_with({{{2.0, -1.5}, {2.0, 1.5}}}));
  EXPECT_FALSE(grid_path(map, {0, 0}, {3.5, 0}, kClearance, GridPathOptions{}));
  // A target inside the clearance of an obstacle is refused, too.
  EXPECT_FALSE(grid_path(map, {0, 0}, {1.8, 0}, kClearance, GridPathOptions{}));
}

TEST(GridPath, NoDetourOutsideTheFieldOfView)
{
  // Nothing was seen behind the robot: a target there is not planned to, and a target ahead
  // whose only way is around through the unseen space behind is not reached either.
  const LocalMap map = scanned(Pose2(), corridor_with({}));
  EXPECT_FALSE(grid_path(map, {0, 0}, {-1.5, 0}, kClearance, GridPathOptions{}));
  EXPECT_TRUE(grid_path(map, {0, 0}, {2.0, 0.5}, kClearance, GridPathOptions{}));
}

TEST(GridPath, ChainAlongTheDetourIsFree)
{
  std::vector<testing::Wall> cup = {{{2.0, -0.5}, {2.0, 0.5}}, {{2.0, -0.5}, {1.4, -0.5}}, {{2.0, 0.5}, {1.4, 0.5}}};
  const LocalMap map = scanned(Pose2(), corridor_with(cup));
  const auto path = grid_path(map, {0, 0}, {3.5, 0}, kClearance, GridPathOptions{});
  ASSERT_TRUE(path);
  ChainPlanner planner(PlannerOptions{});
  const auto c = planner.plan_along(Pose2(), 0.0, *path, 0.0, map, 0.35);
  ASSERT_TRUE(c);
  EXPECT_FALSE(first_collision(c->chain, map, kClearance, 0.02));
  EXPECT_LT((c->chain.end().translation() - Eigen::Vector2d(3.5, 0)).norm(), 1e-3);
  EXPECT_GT(c->predicted_time, c->chain.length() / 0.35);
}

TEST(ChainPlanner, NearMarginOnlyFromWhatMayBeMoving)
{
  // A wall across the corridor at x = 1.5 with a 1.0 m door centred on y = 0.3: the door
  // leaves 0.5 m from its centre line to the frames (> 0.36 clearance, < 0.56 with the near
  // margin) and lies within the first metre.
  std::vector<testing::Wall> walls = corridor_with({{{1.5, -1.5}, {1.5, -0.2}}, {{1.5, 0.8}, {1.5, 1.5}}});
  const Pose2 start(0.8, 0.3, 0.0);
  PlannerOptions o;
  ChainPlanner planner(o);
  LocalMap map(LocalMapOptions{});
  auto scan_at = [&](int64_t us, const std::vector<testing::Wall>& w) {
    const ScanPoints s = testing::scan_points(start, w, time::from_utime(us), map.max_range());
    map.add_scan(s);
    map.rebuild(s.stamp);
  };
  const std::vector<Pose2> goal{Pose2(3.0, 0.3, 0.0)};
  // Just seen, the frames might be people stepping in: the near margin holds the robot.
  scan_at(1'000'000, walls);
  EXPECT_GT(map.moving_size(), 0u);
  EXPECT_FALSE(planner.plan(start, 0.0, goal, map, 0.6));
  // Seen for over a second without a gap: static, and the door is passable.
  for (int64_t us = 1'100'000; us <= 2'200'000; us += 100'000) scan_at(us, walls);
  EXPECT_EQ(map.moving_size(), 0u);
  const auto c = planner.plan(start, 0.0, goal, map, 0.6);
  ASSERT_TRUE(c);
  EXPECT_FALSE(first_collision(c->chain, map, o.robot_radius + o.safety_margin, 0.02));
  // A person steps in beside the path, 0.45 m from it, inside the near margin: the planner
  // holds back.
  auto with_person = walls;
  for (const auto& w : testing::box(1.0, 0.75, 1.3, 1.05)) with_person.push_back(w);
  scan_at(2'300'000, with_person);
  EXPECT_GT(map.moving_size(), 0u);
  EXPECT_FALSE(planner.plan(start, 0.0, goal, map, 0.6));
  // Standing still for over a second, the person counts as static: the plain margin applies.
  for (int64_t us = 2'400'000; us <= 3'500'000; us += 100'000) scan_at(us, with_person);
  EXPECT_EQ(map.moving_size(), 0u);
  EXPECT_TRUE(planner.plan(start, 0.0, goal, map, 0.6));
}

}  // namespace
}  // namespace rgnav::collision_avoidance
