// Giving way (give_way.h): back, away from the target, along the freest line; and the robot
// keeps giving way when the targets are re-sent for the same goal (the localization
// re-expresses them during every turn on the spot).
#include "collision_avoidance/give_way.h"

#include <gtest/gtest.h>

#include <cmath>

#include "collision_avoidance/collision_avoidance.h"
#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

// A map of points (odom frame) seen from the origin.
LocalMap map_of(const std::vector<Eigen::Vector2d>& points)
{
  LocalMap map(LocalMapOptions{});
  ScanPoints s;
  s.stamp = time::from_utime(1'000'000);
  s.points = points;
  map.add_scan(s);
  map.rebuild(s.stamp);
  return map;
}

std::vector<Eigen::Vector2d> wall(Eigen::Vector2d a, Eigen::Vector2d b)
{
  std::vector<Eigen::Vector2d> out;
  const int n = static_cast<int>((b - a).norm() / 0.03);
  for (int i = 0; i <= n; ++i) out.push_back(a + (b - a) * i / std::max(1, n));
  return out;
}

TEST(GiveWay, StraightBackWhenFree)
{
  const LocalMap map = map_of(wall({0.6, -1.0}, {0.6, 1.0}));  // the way ahead is blocked
  const auto w = choose_give_way(map, {0.0, 0.0}, M_PI, 0.36, 0.05, GiveWayOptions{});
  ASSERT_TRUE(w.has_value());
  EXPECT_NEAR(std::fabs(w->heading), M_PI, 1e-9);
  EXPECT_NEAR(w->length, 1.0, 1e-9);
}

TEST(GiveWay, AroundWhatBlocksStraightBack)
{
  // Behind the robot, 0.7 m away, a box across straight back and to its right (seen as the
  // robot faces +x: points behind are remembered from earlier). Back and to the left is free.
  std::vector<Eigen::Vector2d> pts = wall({-0.7, -1.5}, {-0.7, 0.2});
  const LocalMap map = map_of(pts);
  const auto w = choose_give_way(map, {0.0, 0.0}, M_PI, 0.36, 0.05, GiveWayOptions{});
  ASSERT_TRUE(w.has_value());
  // Not straight back (blocked after ~0.3 m): a heading turned toward +y, still leading back.
  EXPECT_GT(geometry::normalize_angle(w->heading), M_PI_2);
  EXPECT_LT(geometry::normalize_angle(w->heading), M_PI - 0.1);
  EXPECT_GE(w->length, GiveWayOptions{}.min_length);
  // The chosen line keeps the clearance all along.
  for (double s = 0.0; s <= w->length; s += 0.05) {
    const Eigen::Vector2d p = s * Eigen::Vector2d(std::cos(w->heading), std::sin(w->heading));
    EXPECT_GE(map.clearance(p, 0.36), 0.36 - 1e-9);
  }
}

TEST(GiveWay, NothingWhenBoxedIn)
{
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 72; ++i) {
    const double a = i * M_PI / 36.0;
    pts.emplace_back(0.55 * std::cos(a), 0.55 * std::sin(a));
  }
  const LocalMap map = map_of(pts);
  EXPECT_FALSE(choose_give_way(map, {0.0, 0.0}, M_PI, 0.36, 0.05, GiveWayOptions{}).has_value());
}

// In a passage 1.1 m wide a person walks up to the robot and stops 0.75 m ahead (at their
// personal space, waiting for the robot to clear their way). After yield_after without headway
// the robot turns around and drives back; the targets re-sent every 100 ms (as the
// localization re-expresses them) must not cut that short.
TEST(GiveWay, SurvivesTargetsResentForTheSameGoal)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  auto world = [](double person_x) {
    std::vector<testing::Wall> w = {{{-4.0, -0.55}, {6.0, -0.55}}, {{-4.0, 0.55}, {6.0, 0.55}}};
    for (const auto& side : testing::box(person_x - 0.2, -0.2, person_x + 0.2, 0.2)) w.push_back(side);
    return w;
  };
  double person_x = 3.0;
  auto scan = [&](const Pose2& pose) { return testing::cast(pose * o.base_from_laser, world(person_x)); };
  Targets t;
  t.goal_id = 5;
  t.poses = {Pose2(3.0, 0.0, 0.0)};
  ca.set_targets(t);
  int64_t us = 1'000'000;
  std::optional<trajectory::Trajectory> give_way;
  for (int i = 0; i < 250 && !give_way; ++i) {
    us += 100'000;
    person_x = std::max(0.95, person_x - 0.06);  // 0.6 m/s, then waits
    ca.on_odometry(time::from_utime(us), Pose2(), 0.0);
    ca.on_scan(time::from_utime(us), scan(Pose2()), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    ca.set_targets(t);
    auto out = ca.update(time::from_utime(us));
    if (out && ca.status().find("giving way") != std::string::npos) give_way = out;
  }
  ASSERT_TRUE(give_way.has_value()) << ca.status();
  ASSERT_EQ(give_way->chain.size(), 2u);
  EXPECT_EQ(give_way->chain[0].kind(), trajectory::Kind::kTurn);
  EXPECT_NEAR(std::fabs(give_way->chain[0].turn_angle()), M_PI, 0.05);
  EXPECT_EQ(give_way->chain[1].kind(), trajectory::Kind::kLine);
  EXPECT_NEAR(give_way->chain[1].length(), o.give_way.length, 1e-9);
  // Turning on the spot, targets re-sent each time: the manoeuvre goes on (keep-alives of
  // the same trajectory, or nothing new), it is not replaced.
  for (int i = 0; i < 20; ++i) {
    us += 100'000;
    const Pose2 turning(0.0, 0.0, 0.15 * i);
    ca.on_odometry(time::from_utime(us), turning, 0.0);
    ca.on_scan(time::from_utime(us), scan(turning), 8.0);
    ca.on_drive_feedback({give_way->id, 1, 0.0, 0.0, 0.0});
    ca.set_targets(t);
    const auto out = ca.update(time::from_utime(us));
    if (out) {
      EXPECT_EQ(out->id, give_way->id) << "step " << i << ": " << ca.status();
    }
  }
  // A new goal ends it: the next trajectory sent is another.
  Targets other = t;
  other.goal_id = 6;
  ca.set_targets(other);
  std::optional<trajectory::Trajectory> next;
  for (int i = 0; i < 30 && !next; ++i) {
    us += 100'000;
    const Pose2 turned(0.0, 0.0, 3.0);
    ca.on_odometry(time::from_utime(us), turned, 0.0);
    ca.on_scan(time::from_utime(us), scan(turned), 8.0);
    ca.on_drive_feedback({give_way->id, 1, 0.0, 0.0, 0.0});
    next = ca.update(time::from_utime(us));
  }
  ASSERT_TRUE(next.has_value()) << ca.status();
  EXPECT_NE(next->id, give_way->id);
}

// The same passage blocked by a box that was always there: no one waits, so no giving way
// (the robot does not drive back a metre from every box it cannot pass).
TEST(GiveWay, NotForABox)
{
  CaOptions o;
  CollisionAvoidance ca(o);
  std::vector<testing::Wall> w = {{{-4.0, -0.55}, {6.0, -0.55}}, {{-4.0, 0.55}, {6.0, 0.55}}};
  for (const auto& side : testing::box(0.75, -0.2, 1.15, 0.2)) w.push_back(side);
  Targets t;
  t.poses = {Pose2(3.0, 0.0, 0.0)};
  ca.set_targets(t);
  int64_t us = 1'000'000;
  for (int i = 0; i < 250; ++i) {
    us += 100'000;
    ca.on_odometry(time::from_utime(us), Pose2(), 0.0);
    ca.on_scan(time::from_utime(us), testing::cast(Pose2() * o.base_from_laser, w), 8.0);
    ca.on_drive_feedback({0, 0, 0.0, 0.0, 0.0});
    ca.update(time::from_utime(us));
    ASSERT_EQ(ca.status().find("giving way"), std::string::npos) << "at step " << i;
  }
}

}  // namespace
}  // namespace rgnav::collision_avoidance
