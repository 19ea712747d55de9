#include "procs/rg_kernel/doorways.h"

#include <gtest/gtest.h>

#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/region_builder.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;

rgmap::LineSegment seg(double ax, double ay, double bx, double by)
{
  rgmap::LineSegment s;
  s.a = Vector2d(ax, ay);
  s.b = Vector2d(bx, by);
  return s;
}

TEST(Doorways, GapOfDoorWidthInAStraightWall)
{
  const DoorwayOptions o;
  // A wall along y = 3 with a 1 m gap between x = 1 and x = 2 (pieces in either order of ends).
  const auto d = find_doorways({seg(0, 3, 1, 3), seg(4, 3.02, 2, 3.0)}, o);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR((d[0].first - Vector2d(1, 3)).norm() + (d[0].second - Vector2d(2, 3)).norm(), 0.0, 1e-9);

  EXPECT_TRUE(find_doorways({seg(0, 3, 1, 3), seg(1.3, 3, 4, 3)}, o).empty());     // 0.3 m: a hole in the wall points
  EXPECT_TRUE(find_doorways({seg(0, 3, 1, 3), seg(3, 3, 5, 3)}, o).empty());       // 2 m: wider than a door
  EXPECT_TRUE(find_doorways({seg(0, 3, 1, 3), seg(2, 3.5, 4, 3.5)}, o).empty());   // not one wall: offset 0.5 m
  EXPECT_TRUE(find_doorways({seg(0, 3, 1, 3), seg(1, 4, 1, 6)}, o).empty());       // a corner, not a wall
  EXPECT_TRUE(find_doorways({seg(0, 3, 2, 3), seg(0.5, 3.05, 1.2, 3.05)}, o).empty());   // overlapping pieces
  EXPECT_TRUE(find_doorways({seg(0, 3, 1, 3), seg(2, 3, 2.2, 3)}, o).empty());     // too short a piece to be wall
  DoorwayOptions off;
  off.enabled = false;
  EXPECT_TRUE(find_doorways({seg(0, 3, 1, 3), seg(2, 3, 4, 3)}, off).empty());
}

TEST(Doorways, WallEndGapFromAPartitionsEndToTheWallItRunsInto)
{
  // A room [0,8]x[0,6] with a partition along x = 4 from the floor wall up to y = 3.5: its line
  // runs on into the top wall 2.5 m further.
  DoorwayOptions o;
  o.wall_end_max_width = 3.0;
  const std::vector<rgmap::LineSegment> room = {seg(0, 6, 8, 6), seg(0, 0, 8, 0), seg(4, 0, 4, 3.5)};
  const auto d = find_doorways(room, o);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR((d[0].first - Vector2d(4, 3.5)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((d[0].second - Vector2d(4, 6)).norm(), 0.0, 1e-9);

  EXPECT_TRUE(find_doorways(room, DoorwayOptions{}).empty());   // off unless asked for
  DoorwayOptions narrow = o;
  narrow.wall_end_max_width = 2.0;
  EXPECT_TRUE(find_doorways(room, narrow).empty());              // wider than asked for

  // The partition's own end face (a thick wall seen end-on) neither makes its end a corner nor
  // puts it in line with another wall.
  auto thick = room;
  thick.push_back(seg(3.85, 3.5, 4.15, 3.5));
  EXPECT_EQ(find_doorways(thick, o).size(), 1u);
  // The corner of a wall across it touching the end: no free end.
  auto corner = room;
  corner.push_back(seg(4, 3.6, 6, 3.6));
  EXPECT_TRUE(find_doorways(corner, o).empty());
  // A door frame's face is not a wall: 0.3 m of wall, extended across a hallway, would cut it at every door.
  EXPECT_TRUE(find_doorways({seg(0, 6, 8, 6), seg(4, 3.2, 4, 3.5)}, o).empty());
  // Something else in the way (a box in the gap) is not the wall the line runs into.
  auto blocked = room;
  blocked.push_back(seg(3.8, 4.5, 4.2, 4.5));
  EXPECT_TRUE(find_doorways(blocked, o).empty());
  // A line running along a wall (not across it) makes no gap.
  EXPECT_TRUE(find_doorways({seg(4, 6, 4, 9), seg(4, 0, 4, 3.5)}, o).empty());
}

TEST(Doorways, WallEndGapIntoACornerButNotAJambOfAnotherWallsOpening)
{
  DoorwayOptions o;
  o.wall_end_max_width = 3.0;
  // The line runs 0.2 m past the end of the wall across it: into the corner it makes.
  EXPECT_EQ(find_doorways({seg(0, 6, 3.8, 6), seg(4, 0, 4, 4.7)}, o).size(), 1u);
  // ... 0.5 m past it: beside it, into nothing.
  EXPECT_TRUE(find_doorways({seg(0, 6, 3.5, 6), seg(4, 0, 4, 4.7)}, o).empty());
  // lab_intel: a partition between two rooms open onto a hallway ends flush with the rooms' front
  // walls (along y = 3.5, 1 m away); its line runs on across the hallway into the hallway's
  // far wall (y = 6). The opening lies along the front walls' line, not across the hallway: the
  // one gap is the front wall's, from its end to the partition.
  const auto d = find_doorways({seg(0, 6, 8, 6), seg(4, 0, 4, 3.5), seg(5, 3.5, 7, 3.5)}, o);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR(d[0].first.y(), 3.5, 1e-9);
  EXPECT_NEAR(d[0].second.y(), 3.5, 1e-9);
}

TEST(Doorways, OnlyTheOnesThePathDidNotGoThrough)
{
  const std::vector<Line> doors = {{Vector2d(1, 3), Vector2d(2, 3)}, {Vector2d(3, 3), Vector2d(4, 3)}};
  const std::vector<Vector2d> path = {Vector2d(1.5, 1), Vector2d(1.5, 2.8), Vector2d(1.5, 3.3), Vector2d(1.5, 4)};
  const auto left = doorways_not_crossed(doors, path);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].first, Vector2d(3, 3));
  EXPECT_EQ(doorways_not_crossed(doors, {}).size(), 2u);
}

TEST(Doorways, StepThroughTheGap)
{
  const DoorwayOptions o;
  const std::vector<rgmap::LineSegment> wall = {seg(0, 3, 1, 3), seg(2, 3, 4, 3)};
  const auto d = doorway_stepped_through(wall, Vector2d(1.5, 2.8), Vector2d(1.5, 3.2), o);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(0.5 * (d->first + d->second).x(), 1.5, 1e-9);
  EXPECT_FALSE(doorway_stepped_through(wall, Vector2d(1.5, 2.0), Vector2d(1.5, 2.8), o));   // not through yet
  EXPECT_FALSE(doorway_stepped_through(wall, Vector2d(3.0, 2.8), Vector2d(3.0, 3.2), o));   // through the wall: not a door
  EXPECT_FALSE(doorway_stepped_through(wall, Vector2d(1.5, 1.0), Vector2d(1.5, 4.0), o));   // a 3 m jump
}

TEST(GatewayGeometry, OutlineHasFourSidesOpenWhereTheRegionLies)
{
  EXPECT_EQ(gateway_edges({Vector2d(0, 0), Vector2d(0, 1)}).size(), 1u);
  // A crossing from x = 4 to 6 across a hallway y in [0, 2]: entry x = 4, ahead x = 6.
  const std::vector<Vector2d> box = {Vector2d(4, 2), Vector2d(6, 2), Vector2d(6, 0), Vector2d(4, 0)};
  EXPECT_EQ(gateway_edges(box).size(), 4u);
  // Nobody's robot near it: all four sides end beams.
  EXPECT_EQ(clip_lines(box, {Vector2d(20, 20)}, {2.0}).size(), 4u);
  // The region west of it: its beams may enter through the entry side (x = 4), not leave elsewhere.
  const auto west = clip_lines(box, {Vector2d(2, 1), Vector2d(3.5, 1)}, {2.0});
  ASSERT_EQ(west.size(), 3u);
  for (const auto& [a, b] : west) EXPECT_FALSE(a.x() == 4 && b.x() == 4);
  // A robot inside the box is beyond no side.
  EXPECT_EQ(clip_lines(box, {Vector2d(5, 1)}, {2.0}).size(), 4u);
  // Nor is one 5 cm past a side once a minimum depth is asked for: it stood on the line.
  EXPECT_EQ(clip_lines(box, {Vector2d(3.95, 1)}, {2.0}).size(), 3u);
  EXPECT_EQ(clip_lines(box, {Vector2d(3.95, 1)}, {2.0, 0.15}).size(), 4u);
  EXPECT_EQ(clip_lines(box, {Vector2d(3.8, 1)}, {2.0, 0.15}).size(), 3u);
  // A line gateway ends beams whichever side the robot is on.
  EXPECT_EQ(clip_lines({Vector2d(4, 1), Vector2d(4, 2)}, {Vector2d(3, 1.5)}, {2.0}).size(), 1u);
  // A door line lengthened at both ends: beams grazing past the jambs' visible edges end too.
  const auto longer = clip_lines({Vector2d(4, 1), Vector2d(4, 2)}, {Vector2d(3, 1.5)}, {2.0}, 0.5);
  ASSERT_EQ(longer.size(), 1u);
  EXPECT_NEAR(longer[0].first.y(), 0.5, 1e-12);
  EXPECT_NEAR(longer[0].second.y(), 2.5, 1e-12);
  EXPECT_NEAR(longer[0].first.x(), 4.0, 1e-12);
}

// Room A [0,4]x[0,3] with an open door (x = 4, y in [1, 2]) into room B; A's robot looks
// through it. The region's freespace must stop at the doorway, with no gateway known.
RegionBuilder room_a_looking_through_the_door(bool step_through)
{
  RegionBuilder b{RegionBuildOptions{}};
  int64_t id = 1;
  auto scan_at = [&](double x, double heading) {
    StoredScan s;
    s.scan_id = id;
    s.utime = id++;
    s.region_from_laser = geometry::Pose2(x, 1.5, heading);
    s.laser_points = testing::cast(testing::two_rooms(), s.region_from_laser);
    b.add_scan(s);
  };
  for (double x = 1.0; x < 3.5; x += 0.2) scan_at(x, 0);
  for (double x = 3.4; x > 0.9; x -= 0.2) scan_at(x, M_PI);   // the wall beside the door, seen both ways
  for (double x = 1.0; x < 3.5; x += 0.2) scan_at(x, 0);
  if (step_through)
    for (double x = 4.3; x < 6.0; x += 0.2) scan_at(x, 0);
  return b;
}

TEST(RegionBuilder, FreespaceStopsAtADoorwayItsRobotNeverWentThrough)
{
  const RegionBuilder b = room_a_looking_through_the_door(false);
  rgmap::Region r;
  b.describe(&r, {}, true);
  EXPECT_TRUE(r.freespace.is_free(Vector2d(2.0, 1.5)));
  EXPECT_TRUE(r.freespace.is_free(Vector2d(3.8, 1.5)));    // in front of the door
  EXPECT_FALSE(r.freespace.is_free(Vector2d(5.0, 1.5)));   // room B, seen through it
  EXPECT_FALSE(r.freespace.is_free(Vector2d(6.5, 1.5)));
  EXPECT_LT(r.bbox_max.x(), 4.1);

  // The robot went through: a door the detector missed, the region holds both rooms.
  const RegionBuilder through = room_a_looking_through_the_door(true);
  through.describe(&r, {}, true);
  EXPECT_TRUE(r.freespace.is_free(Vector2d(5.0, 1.5)));
  EXPECT_TRUE(r.freespace.is_free(Vector2d(2.0, 1.5)));
}

}  // namespace
}  // namespace rgnav::rg_kernel
