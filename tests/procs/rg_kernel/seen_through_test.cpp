// Points on what moved are left out of the line map (seen_through.h, RegionBuildOptions::
// seen_through_margin): a person walking along a hallway half a metre from its wall, whose
// place no 5 x 5 block of free cells covers.
#include <gtest/gtest.h>

#include "procs/rg_kernel/region_builder.h"
#include "procs/rg_kernel/seen_through.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;
using testing::Pillar;

// A 2 m hallway y in [0, 2], x in [0, 14], closed at both ends.
std::vector<testing::Wall> hallway()
{
  return {{Vector2d(0, 0), Vector2d(14, 0)}, {Vector2d(0, 2), Vector2d(14, 2)}, {Vector2d(0, 0), Vector2d(0, 2)},
          {Vector2d(14, 0), Vector2d(14, 2)}};
}

// Points of a scan (region frame) on the person (within 5 cm of the disc) and the others.
struct Split
{
  std::vector<Vector2d> person, rest;
};
Split split(const std::vector<Vector2d>& laser_points, const geometry::Pose2& pose, const Pillar& p)
{
  Split s;
  for (const auto& lp : laser_points) {
    const Vector2d q = pose * lp;
    ((q - p.c).norm() < p.r + 0.05 ? s.person : s.rest).push_back(q);
  }
  return s;
}

TEST(SeenThrough, APersonsPlaceIsSeenThroughWhenTheyHaveGoneAWallNever)
{
  const Pillar person{Vector2d(5, 1.5), 0.22};
  // A laser that sees the whole hallway (20 m): every beam has a return.
  const geometry::Pose2 at_a(1, 1, 0), at_b(2, 1, 0);
  const auto a = testing::cast(hallway(), at_a, 20.0, {person});
  const Split seen = split(a, at_a, person);
  ASSERT_GT(seen.person.size(), 3u);
  const BeamView later(at_b, testing::cast(hallway(), at_b, 20.0), 20.0);   // the person has gone
  const BeamView still(at_b, testing::cast(hallway(), at_b, 20.0, {person}), 20.0);   // still there
  const double min_cos = std::cos(70.0 * M_PI / 180.0);
  // Beams are trusted as free space only as far as the region carves (its freespace max range).
  const BeamView near_only(at_b, testing::cast(hallway(), at_b, 20.0), 3.0);
  for (const auto& p : seen.person) {
    EXPECT_TRUE(later.sees_through(p, Vector2d::Zero(), 0.3, min_cos)) << p.transpose();
    EXPECT_FALSE(still.sees_through(p, Vector2d::Zero(), 0.3, min_cos)) << p.transpose();
    EXPECT_FALSE(near_only.sees_through(p, Vector2d::Zero(), 0.3, min_cos)) << p.transpose();
  }
  // The walls, seen from anywhere along the hallway, never (their normals from the scan).
  std::vector<Vector2d> rest = seen.rest;
  const auto normals = point_normals(rest, 0.25);
  for (const geometry::Pose2& from : {at_b, geometry::Pose2(6, 0.5, 0.3), geometry::Pose2(12, 1.5, M_PI)}) {
    const BeamView v(from, testing::cast(hallway(), from, 20.0), 20.0);
    for (size_t i = 0; i < rest.size(); ++i) EXPECT_FALSE(v.sees_through(rest[i], normals[i], 0.3, min_cos)) << rest[i].transpose();
  }
}

TEST(SeenThrough, BeamsWithoutReturnTellNothing)
{
  // The later scan reaches only 1 m: its beams toward the person's place have no return, and a
  // missing return is no evidence of free space (glass, black surfaces, out of range).
  const Pillar person{Vector2d(4, 1.5), 0.22};
  const geometry::Pose2 at(1, 1, 0);
  const Split seen = split(testing::cast(hallway(), at, 8.0, {person}), at, person);
  const BeamView short_sighted(at, testing::cast(hallway(), at, 1.0), 20.0);
  for (const auto& p : seen.person) EXPECT_FALSE(short_sighted.sees_through(p, Vector2d::Zero(), 0.3, 0.34));
}

// The robot drives along the hallway; a person walks ahead of it, half a metre from the wall,
// a little faster. Every scan sees them at a new place that earlier scans saw empty (and later
// ones see empty again). With the rule, the line map has nothing between the walls; off, the
// person's trail is segments across the hallway (the 5 x 5 free-cell rule alone does not reach
// there: the wall's cells are never free).
TEST(RegionBuilder, WhatWalksAlongTheHallwayIsNoPartOfTheLineMap)
{
  auto ghosts = [](const RegionBuilder& b) {
    int n = 0;
    for (const auto& s : b.segments()) {
      const Vector2d m = 0.5 * (s.a + s.b);
      if (m.y() > 0.15 && m.y() < 1.85 && m.x() > 0.15 && m.x() < 13.85) ++n;
    }
    return n;
  };
  auto walls = [](const RegionBuilder& b) {
    int n = 0;
    for (const auto& s : b.segments())
      if ((s.b - s.a).norm() > 1.0) ++n;
    return n;
  };
  for (const double margin : {0.3, 0.0}) {
    RegionBuildOptions o;
    o.seen_through_margin = margin;
    RegionBuilder b{o};
    for (int k = 0; k < 40; ++k) {
      StoredScan s;
      s.scan_id = k + 1;
      s.utime = (k + 1) * 300'000;
      s.region_from_laser = geometry::Pose2(1.0 + 0.15 * k, 1.0, 0);
      const Pillar person{Vector2d(3.0 + 0.25 * k, 1.5), 0.22};
      s.laser_points = testing::cast(hallway(), s.region_from_laser, 8.0, {person});
      b.add_scan(s);
    }
    if (margin > 0) {
      EXPECT_EQ(ghosts(b), 0) << "with the rule";
    } else {
      EXPECT_GT(ghosts(b), 0) << "without it";
    }
    EXPECT_GE(walls(b), 2) << "the hallway's walls stay";
    // The exact description (a finalised region) holds the same line map.
    rgmap::Region r;
    b.describe(&r, {}, true);
    int in_hall = 0;
    for (const auto& s : r.segments) {
      const Vector2d m = 0.5 * (s.a + s.b);
      if (m.y() > 0.15 && m.y() < 1.85 && m.x() > 0.15 && m.x() < 13.85) ++in_hall;
    }
    EXPECT_EQ(in_hall > 0, margin == 0.0);
  }
}

// A person stands still in the hallway while the region's robot looks at them: none of its own
// scans sees through them. The next region's robot (beyond a gateway) sees the place empty: the
// person leaves this region's line map when it is described again.
TEST(RegionBuilder, WhatAScanOfAnotherRegionSeesThroughLeavesTheLineMap)
{
  auto in_hall = [](const std::vector<rgmap::LineSegment>& segs) {
    int n = 0;
    for (const auto& s : segs) {
      const Vector2d m = 0.5 * (s.a + s.b);
      if (m.y() > 0.15 && m.y() < 1.85 && m.x() > 0.15 && m.x() < 13.85) ++n;
    }
    return n;
  };
  auto with_person = hallway();
  with_person.push_back({Vector2d(6.0, 1.1), Vector2d(6.0, 1.6)});   // their front, 0.4 m from the wall
  RegionBuilder b{RegionBuildOptions{}};
  for (int k = 0; k < 10; ++k) {
    StoredScan s;
    s.scan_id = k + 1;
    s.utime = (k + 1) * 300'000;
    s.region_from_laser = geometry::Pose2(1.0 + 0.15 * k, 1.0, 0);
    s.laser_points = testing::cast(with_person, s.region_from_laser);
    b.add_scan(s);
  }
  ASSERT_GT(in_hall(b.segments()), 0) << "standing still, the person is what the region's scans saw";
  // The other region's scan, given in this region's frame, from farther along and facing back.
  const geometry::Pose2 beyond(7.5, 1.0, M_PI);   // the hallway's end within its 8 m
  EXPECT_TRUE(b.see_through_by(beyond, testing::cast(hallway(), beyond)));
  EXPECT_FALSE(b.see_through_by(beyond, testing::cast(hallway(), beyond))) << "already left out";
  rgmap::Region r;
  b.describe(&r, {}, true);
  EXPECT_EQ(in_hall(r.segments), 0);
  EXPECT_GE(r.segments.size(), 2u) << "the walls stay";
  // Off, nothing is seen through.
  RegionBuildOptions off;
  off.seen_through_margin = 0;
  RegionBuilder c{off};
  StoredScan s;
  s.scan_id = 1;
  s.region_from_laser = geometry::Pose2(1.0, 1.0, 0);
  s.laser_points = testing::cast(with_person, s.region_from_laser);
  c.add_scan(s);
  EXPECT_FALSE(c.see_through_by(beyond, testing::cast(hallway(), beyond)));
}

}  // namespace
}  // namespace rgnav::rg_kernel
