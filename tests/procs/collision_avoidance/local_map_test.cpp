#include "collision_avoidance/local_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scan_fixture.h"

namespace rgnav::collision_avoidance {
namespace {

TEST(LocalMap, ClearanceFromScansInOdomFrame)
{
  LocalMap map(LocalMapOptions{});
  ScanPoints s;
  s.stamp = time::from_utime(1'000'000);
  s.odom_from_base = Pose2(1.0, 2.0, M_PI / 2);
  s.points = {{1.0, 0.0}};  // 1 m ahead of a robot facing +y: odom (1, 3)
  map.add_scan(s);
  map.rebuild(time::from_utime(1'100'000));
  EXPECT_NEAR(map.clearance({1.0, 2.5}, 1.0), 0.5, 1e-9);
  EXPECT_TRUE(std::isinf(map.clearance({3.0, 3.0}, 1.0)));
  // Old scans fall out.
  map.rebuild(time::from_utime(3'000'000));
  EXPECT_EQ(map.size(), 0u);
}

TEST(LocalMap, DistanceFieldShortcutAgreesWithExactSearch)
{
  // The field only answers "nothing within r"; wherever something is within r the exact
  // distance must come back. Brute force over random points and queries.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 4.0), ur(0.05, 2.4);
  LocalMap map(LocalMapOptions{});
  ScanPoints s;
  s.stamp = time::from_utime(1'000'000);
  for (int i = 0; i < 300; ++i) s.points.emplace_back(u(rng), u(rng));
  map.add_scan(s);
  map.rebuild(s.stamp);
  for (int q = 0; q < 5000; ++q) {
    const Eigen::Vector2d p(1.5 * u(rng), 1.5 * u(rng));
    const double r = ur(rng);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& pt : s.points) best = std::min(best, (pt - p).norm());
    const double got = map.clearance(p, r);
    if (best <= r) {
      ASSERT_NEAR(got, best, 1e-9) << "query " << p.transpose() << " r " << r;
    } else {
      ASSERT_TRUE(std::isinf(got)) << "query " << p.transpose() << " r " << r;
    }
  }
}

TEST(LocalMap, NewlySeenPartOfAStaticFaceIsNotPossiblyMoving)
{
  // A wall face seen for 1.5 s (static); then the next 0.12 m of it (cells right beside the
  // static ones) come into view, and a blob appears 1 m away from everything. Only the blob
  // may be a person stepping in.
  LocalMap map(LocalMapOptions{});
  auto scan = [](int64_t us, bool more) {
    ScanPoints s;
    s.stamp = time::from_utime(us);
    for (double y = -1.0; y <= 0.0 + 1e-9; y += 0.02) s.points.emplace_back(2.0, y);
    if (more) {
      for (double y = 0.02; y <= 0.12 + 1e-9; y += 0.02) s.points.emplace_back(2.0, y);
      for (double a = -0.5; a <= 0.5; a += 0.1) s.points.emplace_back(1.0 + 0.1 * std::cos(a), 1.0 + 0.1 * std::sin(a));
    }
    return s;
  };
  int64_t t = 1'000'000;
  for (; t < 2'500'000; t += 26'667) map.add_scan(scan(t, false));
  map.add_scan(scan(t, true));
  map.rebuild(time::from_utime(t));
  // Possibly moving points within 0.2 m of the blob, none near the wall's new end.
  EXPECT_LT(map.clearance_moving({1.0, 1.0}, 0.5), 0.2);
  EXPECT_TRUE(std::isinf(map.clearance_moving({2.0, 0.12}, 0.5)));
  EXPECT_LT(map.clearance({2.0, 0.12}, 0.5), 0.05);  // still an obstacle, with the plain margin
}

TEST(LocalMap, APersonStandsApartFromTheWallsAPieceOfWallDoesNot)
{
  // A hallway 1.1 m wide along x, the laser in it at the origin facing +x; a person (a 0.4 m
  // box) 2.5 m ahead in the middle. The walls' pieces 2-4 m ahead are seen at a grazing angle:
  // with 1 degree beams, the beam beyond such a piece ends 0.3 m farther or more (as it would
  // beside a person), but the beam before it nearer. (A piece of wall hidden for a moment
  // and seen again looks like someone who walked up and stopped; a piece of the wall that
  // moves along it as the robot turns, like someone walking.)
  const std::vector<testing::Wall> hallway = {{{-3.0, -0.55}, {8.0, -0.55}}, {{-3.0, 0.55}, {8.0, 0.55}}};
  auto with_person = hallway;
  for (const auto& side : testing::box(2.5, -0.2, 2.9, 0.2)) with_person.push_back(side);
  LocalMap map(LocalMapOptions{});
  map.add_scan(testing::scan_points(Pose2(), with_person, time::from_utime(1'000'000), map.max_range()));
  map.rebuild(time::from_utime(1'000'000));
  constexpr double kRadius = 0.3, kJump = 0.3;
  EXPECT_TRUE(map.stands_apart({2.6, 0.0}, kRadius, kJump));
  for (const double x : {2.0, 3.0, 4.0})
    for (const double y : {-0.55, 0.55}) EXPECT_FALSE(map.stands_apart({x, y}, kRadius, kJump)) << x << " " << y;
  // The same pieces of wall with nobody in the hallway; and a wall across it, head-on.
  LocalMap empty(LocalMapOptions{});
  auto shut = hallway;
  shut.push_back({{5.0, -0.55}, {5.0, 0.55}});
  empty.add_scan(testing::scan_points(Pose2(), shut, time::from_utime(1'000'000), empty.max_range()));
  empty.rebuild(time::from_utime(1'000'000));
  for (const double x : {2.5, 3.5})
    for (const double y : {-0.55, 0.55}) EXPECT_FALSE(empty.stands_apart({x, y}, kRadius, kJump)) << x << " " << y;
  EXPECT_FALSE(empty.stands_apart({5.0, 0.0}, kRadius, kJump));
}

TEST(LocalMap, GridPointsAndScanCount)
{
  LocalMapOptions o;
  o.max_scans = 2;
  LocalMap map(o);
  for (int i = 0; i < 3; ++i) {
    ScanPoints s;
    s.stamp = time::from_utime(1'000'000 + i);
    s.points = {{1.0 + i, 0.0}};
    map.add_scan(s);
  }
  map.set_grid_points(time::from_utime(1'000'000), {{0.0, -0.4}});
  map.rebuild(time::from_utime(1'000'010));
  EXPECT_EQ(map.size(), 3u);  // two scans + one grid point
  EXPECT_NEAR(map.clearance({0.0, 0.0}, 1.0), 0.4, 1e-9);
}

// A loaded vision delivers its grid seconds after the frame: a map still, until a newer one
// comes, for at most the memory time.
TEST(LocalMap, ALateGridHoldsUntilTheMemoryTime)
{
  LocalMapOptions o;
  LocalMap map(o);
  map.set_grid_points(time::from_utime(1'000'000), {{0.0, -0.4}});
  map.rebuild(time::from_utime(1'000'000 + static_cast<int64_t>((o.max_age + 2.0) * 1e6)));
  EXPECT_EQ(map.size(), 1u) << "older than max_age: still the newest grid";
  map.rebuild(time::from_utime(1'000'000 + static_cast<int64_t>((o.memory + 0.5) * 1e6)));
  EXPECT_EQ(map.size(), 0u) << "older than the memory time: gone";
}


// A scan from a robot at `pose` seeing one obstacle point `hit` (base frame) and free space
// out to 4 m elsewhere, over a 180 degree field of view.
ScanPoints scan_with(time::Time stamp, const Pose2& pose, const std::vector<Eigen::Vector2d>& hits)
{
  ScanPoints s;
  s.stamp = stamp;
  s.odom_from_base = pose;
  s.points = hits;
  for (int b = 0; b <= 180; ++b) {
    const double a = (b - 90) * M_PI / 180.0;
    double r = 4.0;
    for (const auto& h : hits)
      if (std::fabs(std::atan2(h.y(), h.x()) - a) < 0.6 * M_PI / 180.0) r = std::min(r, h.norm());
    s.outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return s;
}

TEST(LocalMap, RemembersStaticObstaclesOutOfViewUntilSeenThrough)
{
  LocalMapOptions o;
  LocalMap map(o);
  // Two seconds looking at a box corner 1.5 m ahead: static.
  int64_t us = 1'000'000;
  for (; us < 3'000'000; us += 26'667) map.add_scan(scan_with(time::from_utime(us), Pose2(0, 0, 0), {{1.5, 0.0}}));
  // Turned around: the box is behind the laser now, for longer than max_age.
  for (; us < 6'000'000; us += 26'667) map.add_scan(scan_with(time::from_utime(us), Pose2(0, 0, M_PI), {}));
  map.rebuild(time::from_utime(us));
  EXPECT_NEAR(map.clearance({1.0, 0.0}, 1.0), 0.5, 0.04);
  // Turned back: the beams now pass where the box was (it was moved away): forgotten.
  map.add_scan(scan_with(time::from_utime(us), Pose2(0, 0, 0), {}));
  map.rebuild(time::from_utime(us));
  EXPECT_TRUE(std::isinf(map.clearance({1.0, 0.0}, 1.0)));
}

TEST(LocalMap, DoesNotRememberWhatWasSeenOnlyBriefly)
{
  LocalMap map(LocalMapOptions{});
  int64_t us = 1'000'000;
  // A person passing through the view for 0.3 s, then gone out of view.
  for (; us < 1'300'000; us += 26'667) map.add_scan(scan_with(time::from_utime(us), Pose2(0, 0, 0), {{1.5, 0.0}}));
  for (; us < 4'000'000; us += 26'667) map.add_scan(scan_with(time::from_utime(us), Pose2(0, 0, M_PI), {}));
  map.rebuild(time::from_utime(us));
  EXPECT_TRUE(std::isinf(map.clearance({1.0, 0.0}, 1.0)));
  EXPECT_EQ(map.remembered_size(), 0u);
}

}  // namespace
}  // namespace rgnav::collision_avoidance
