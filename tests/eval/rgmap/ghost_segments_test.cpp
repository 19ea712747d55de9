#include "ghost_segments.h"

#include <gtest/gtest.h>

namespace rgnav::rgmap_pipeline {
namespace {

using Eigen::Vector2d;

// A wall along y = 0 from x = 0 to 10, a door leaf standing open in a gap of it (10..11), a
// cabinet at (5, 3) and a table whose legs only reach the scan plane.
sim::World world()
{
  sim::World w;
  w.walls.push_back({Vector2d(0, 0), Vector2d(10, 0), 0.0, 2.5});
  sim::Door d;
  d.hinge = Vector2d(10, 0);
  d.latch = Vector2d(11, 0);
  d.open = true;
  w.doors.push_back(d);
  sim::Box b;
  b.center = Vector2d(5, 3);
  b.size = Vector2d(1, 0.5);
  w.boxes.push_back(b);
  sim::Table t;
  t.center = Vector2d(2, 4);
  w.tables.push_back(t);
  return w;
}

// One region, its frame at (1, 2) turned by 90 degrees in the map, and the map placed 0.5 m
// along x in the world: segments given in the world frame are stored in the region's frame.
struct Fixture
{
  rgmap::RgMap map;
  geometry::Pose2 world_from_map{0.5, 0.0, 0.0};
  int64_t region = 0;
  Fixture() { region = map.add_region(geometry::Pose2(1.0, 2.0, M_PI / 2), 0).id; }
  void add(const Vector2d& a, const Vector2d& b)
  {
    const geometry::Pose2 region_from_world = (world_from_map * map.region(region)->map_from_region).inverse();
    map.region(region)->segments.push_back({region_from_world * a, region_from_world * b, 0.01, 10});
  }
};

TEST(GhostSegments, SegmentsOnStaticSurfacesAreNoGhosts)
{
  const StaticSurfaces statics(world(), 0.4);
  Fixture f;
  f.add(Vector2d(1, 0.05), Vector2d(9, 0.05));      // the wall, 5 cm off (noise, the fit)
  f.add(Vector2d(10.1, 0.02), Vector2d(10.9, 0.02)); // the door leaf, standing open
  f.add(Vector2d(4.5, 2.75), Vector2d(5.5, 2.75));  // the cabinet's front
  const auto g = count_ghost_segments(f.map, f.world_from_map, statics);
  EXPECT_EQ(g.segments, 3);
  EXPECT_EQ(g.ghosts, 0);
}

TEST(GhostSegments, SegmentsAwayFromStaticSurfacesAreGhosts)
{
  const StaticSurfaces statics(world(), 0.4);
  Fixture f;
  f.add(Vector2d(3, 1.0), Vector2d(3.3, 1.05));     // a person's legs in the open
  f.add(Vector2d(1, 0.2), Vector2d(9, 0.2));        // along the wall, but 0.2 m off it
  // A table's top is above the scan plane: a segment along its edge, between the legs, is no
  // surface the laser could have seen.
  const sim::Table t = world().tables.front();
  f.add(t.center + Vector2d(-0.3, 0.4), t.center + Vector2d(0.3, 0.4));
  const auto g = count_ghost_segments(f.map, f.world_from_map, statics);
  EXPECT_EQ(g.segments, 3);
  EXPECT_EQ(g.ghosts, 3);
  EXPECT_NEAR(g.ghost_length_m, 0.3 * std::sqrt(1 + 1.0 / 36) + 8 + 0.6, 1e-6);
  ASSERT_EQ(g.ghost_list.size(), 3u);
  EXPECT_NEAR(g.ghost_list.front().first.x(), 3.0, 1e-9);
  EXPECT_NEAR(g.ghost_list.front().first.y(), 1.0, 1e-9);
}

TEST(GhostSegments, JudgedByWhereMostOfItsLengthLies)
{
  const StaticSurfaces statics(world(), 0.4);
  // Perpendicular to the wall from y = 0: the first 0.1 m is near it.
  Fixture near_most;
  near_most.add(Vector2d(2, 0), Vector2d(2, 0.18));   // 0.1 of 0.18 near: most of it
  EXPECT_EQ(count_ghost_segments(near_most.map, near_most.world_from_map, statics).ghosts, 0);
  Fixture away_most;
  away_most.add(Vector2d(2, 0), Vector2d(2, 0.22));   // 0.1 of 0.22 near: less than half
  EXPECT_EQ(count_ghost_segments(away_most.map, away_most.world_from_map, statics).ghosts, 1);
  EXPECT_NEAR(statics.share_away(Vector2d(2, 0), Vector2d(2, 1), 0.1), 0.9, 0.03);
}

TEST(GhostSegments, MergedRegionsAreNotCounted)
{
  const StaticSurfaces statics(world(), 0.4);
  Fixture f;
  f.add(Vector2d(3, 1.0), Vector2d(3.3, 1.0));
  f.map.region(f.region)->state = rgmap::Region::State::kMerged;   // its place is another region's
  const auto g = count_ghost_segments(f.map, f.world_from_map, statics);
  EXPECT_EQ(g.segments, 0);
  EXPECT_EQ(g.ghosts, 0);
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline
