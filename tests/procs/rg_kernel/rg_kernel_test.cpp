#include "procs/rg_kernel/rg_kernel.h"

#include <gtest/gtest.h>

#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;

struct Drive
{
  RgKernel kernel{KernelOptions{}};
  std::vector<testing::Wall> walls = testing::two_rooms();
  int64_t next_id = 1;
  int64_t t = 1'000'000;

  void scan_at(const geometry::Pose2& pose)
  {
    ScanInput s;
    s.scan_id = next_id++;
    s.utime = (t += 200'000);
    s.map_from_base = pose;
    s.laser_points = testing::cast(walls, pose);
    kernel.add_scan(s);
  }
  void traverse_door(double x, double heading)
  {
    GatewayEventInput e;
    e.utime = (t += 1000);
    e.kind = GatewayEventInput::Kind::kTraversed;
    e.track_id = 1;
    e.cls = rgmap::GatewayClass::kDoor;
    e.map_from_base = geometry::Pose2(x, 1.5, heading);
    e.gateway_points = {Vector2d(4, 1), Vector2d(4, 2)};
    e.direction = heading;
    kernel.add_gateway_event(e);
  }
};

TEST(RgKernel, DoorSplitsTwoRoomsAndFiltersBeamsThroughIt)
{
  Drive d;
  for (double x = 1.0; x < 3.9; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));
  d.traverse_door(4.3, 0);
  for (double x = 4.5; x < 7.5; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));

  const auto& m = d.kernel.map();
  ASSERT_EQ(m.regions().size(), 2u);
  ASSERT_EQ(m.gateways().size(), 1u);
  const auto& g = m.gateways().begin()->second;
  EXPECT_EQ(g.region_a, 1);
  EXPECT_EQ(g.region_b, 2);
  EXPECT_EQ(g.cls, rgmap::GatewayClass::kDoor);
  EXPECT_EQ(m.current_region, 2);
  EXPECT_TRUE(m.consistency_problems().empty());

  const auto r1 = d.kernel.describe_region(1);
  EXPECT_EQ(r1.state, rgmap::Region::State::kFinalised);
  // In-region measurements only: room A ends at the wall x = 4 (room frame = first pose (1, 1.5)).
  EXPECT_LT(r1.bbox_max.x(), 3.0 + 0.1);
  EXPECT_GT(r1.bbox_max.x(), 3.0 - 0.1);
  EXPECT_TRUE(r1.freespace.is_free(Vector2d(1.0, 0.0)));    // (2, 1.5) in the map
  EXPECT_FALSE(r1.freespace.is_free(Vector2d(5.0, 0.0)));   // (6, 1.5): room B, seen through the door
  // The line map still holds what was seen through the door (for localization).
  bool far_wall_seen = false;
  for (const auto& s : r1.segments) far_wall_seen = far_wall_seen || (s.a.x() > 6.5 && s.b.x() > 6.5);
  EXPECT_TRUE(far_wall_seen);

  // Transform between the regions' frames: region 2's frame is the pose after the door.
  EXPECT_NEAR(g.region_a_from_region_b.x(), 3.3, 1e-9);
  const auto stats = d.kernel.stats();
  EXPECT_GT(stats.compression, 20.0);
}

TEST(RgKernel, CrossingBackReentersTheKnownRegion)
{
  Drive d;
  for (double x = 1.0; x < 3.9; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));
  d.traverse_door(4.3, 0);
  for (double x = 4.5; x < 7.5; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));
  d.traverse_door(3.7, M_PI);
  d.scan_at(geometry::Pose2(3.0, 1.5, M_PI));
  const auto& m = d.kernel.map();
  EXPECT_EQ(m.regions().size(), 2u);
  EXPECT_EQ(m.gateways().size(), 1u);
  EXPECT_EQ(m.current_region, 1);
  EXPECT_EQ(m.gateways().begin()->second.traversals, 2);
  EXPECT_EQ(m.region(2)->state, rgmap::Region::State::kFinalised);
}

TEST(RgKernel, KnownPlaceWithoutGatewayIsMergedAndGatewayNeutralized)
{
  // Diss. 6.1.1 (circular hallway / missed gateway): after leaving room A through the door,
  // the robot comes back into room A's area without any gateway event. The current region is
  // room A seen again: it is merged into A and the door now has A on both sides.
  Drive d;
  for (double x = 1.0; x < 3.9; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));
  d.traverse_door(4.3, 0);
  for (double x = 4.5; x < 5.5; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));
  d.walls.pop_back();  // the door wall vanishes: pretend a loop brought the robot back unseen
  d.walls.pop_back();
  for (int k = 0; k < 20; ++k) d.scan_at(geometry::Pose2(1.5 + 0.05 * k, 1.2, M_PI));
  const auto& m = d.kernel.map();
  EXPECT_EQ(m.region(2)->state, rgmap::Region::State::kMerged);
  EXPECT_EQ(m.resolve(2), 1);
  EXPECT_EQ(m.current_region, 1);
  EXPECT_TRUE(m.gateways().begin()->second.neutralized);
  EXPECT_TRUE(m.consistency_problems().empty());
  EXPECT_EQ(d.kernel.stats().regions, 1);
}

TEST(RgKernel, LateTraversalEventNeitherCarvesTheNextRoomNorMergesIt)
{
  // The detector reports a traversal once the robot is through the door: the scans taken
  // between the door and the event saw room B from inside it. Kept in room A they carved B
  // into A's freespace, and B's first robot positions then "recognised" A: every room entered
  // was merged into the hallway it came from (issue 8, office world: 26 regions merged away).
  Drive d;
  for (double x = 1.0; x < 3.9; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));
  for (double x = 4.1; x < 4.6; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));   // through already
  d.traverse_door(4.6, 0);
  for (double x = 4.8; x < 7.5; x += 0.2) d.scan_at(geometry::Pose2(x, 1.5, 0));

  const auto& m = d.kernel.map();
  ASSERT_EQ(m.regions().size(), 2u);
  EXPECT_EQ(m.region(2)->state, rgmap::Region::State::kOpen);
  EXPECT_EQ(m.current_region, 2);
  EXPECT_FALSE(m.gateways().begin()->second.neutralized);
  const auto r1 = d.kernel.describe_region(1);
  EXPECT_FALSE(r1.freespace.is_free(Vector2d(4.0, 0.0)));   // (5, 1.5): room B
  EXPECT_TRUE(r1.freespace.is_free(Vector2d(2.0, 0.0)));    // (3, 1.5): room A
  EXPECT_EQ(r1.nscans, 15);                                 // x = 1.0 .. 3.8
  EXPECT_EQ(d.kernel.describe_region(2).nscans, 3 + 14);    // the late ones are B's
  EXPECT_EQ(d.kernel.stats().regions, 2);
}

TEST(KnownPlaces, NeedsTheRegionsOwnRobotToHaveSeenThePlaceInRegion)
{
  // Room A's robot looked through the open door (not a gateway then): A's freespace holds a
  // wedge of room B. Being in that wedge is no evidence of being in A.
  rgmap::RgMap map;
  rgmap::Region& a = map.add_region(geometry::Pose2(1.0, 1.5, 0), 1);
  std::map<int64_t, RegionBuilder> builders;
  RegionBuilder& b = builders.emplace(a.id, RegionBuilder(RegionBuildOptions{})).first->second;
  int64_t id = 1;
  for (double x = 1.0; x < 3.9; x += 0.2) {
    StoredScan s;
    s.scan_id = id;
    s.utime = id++;
    s.region_from_laser = geometry::Pose2(x - 1.0, 0, 0);
    s.laser_points = testing::cast(testing::two_rooms(), geometry::Pose2(x, 1.5, 0));
    b.add_scan(s);
  }
  b.describe(&a, {}, true);
  a.state = rgmap::Region::State::kFinalised;
  ASSERT_TRUE(a.freespace.is_free(Vector2d(4.5, 0.0)));    // (5.5, 1.5) in B, seen through the door

  const KnownPlaceOptions o;   // 1.5 m
  {
    const KnownPlaces known(map, builders, 0, o);
    EXPECT_EQ(known.region_holding(Vector2d(2.0, 1.2)), a.id);   // where A's robot was
    EXPECT_EQ(known.region_holding(Vector2d(4.6, 1.5)), a.id);   // door unknown: indistinguishable
    EXPECT_EQ(known.region_holding(Vector2d(6.0, 1.5)), 0);      // in A's bitmap, but 2.2 m from its robot
    EXPECT_EQ(known.region_holding(Vector2d(6.0, 0.5)), 0);      // not even in A's bitmap
    EXPECT_EQ(KnownPlaces(map, builders, a.id, o).region_holding(Vector2d(2.0, 1.2)), 0);   // excluded
  }
  // The door becomes a gateway (crossed later, from B's side): A's robot saw B only through it.
  rgmap::Gateway& g = map.add_gateway(rgmap::GatewayClass::kDoor, a.id, 2);
  g.gateway_points = {Vector2d(3.0, -0.5), Vector2d(3.0, 0.5)};   // x = 4, y in [1, 2] in the map
  const KnownPlaces known(map, builders, 0, o);
  EXPECT_EQ(known.region_holding(Vector2d(4.6, 1.5)), 0);
  EXPECT_EQ(known.region_holding(Vector2d(3.5, 1.5)), a.id);
}

TEST(RgKernel, CorrectedScanIsReplacedNotDuplicated)
{
  Drive d;
  ScanInput s;
  s.scan_id = 42;
  s.utime = 5;
  s.map_from_base = geometry::Pose2(1.0, 1.6, 0);  // 10 cm off
  s.laser_points = testing::cast(d.walls, geometry::Pose2(1.0, 1.5, 0));
  EXPECT_TRUE(d.kernel.add_scan(s));
  const auto before = d.kernel.stats();
  s.revision = 1;
  s.map_from_base = geometry::Pose2(1.0, 1.5, 0);
  EXPECT_TRUE(d.kernel.add_scan(s));
  EXPECT_FALSE(d.kernel.add_scan(s));  // same revision again: nothing to do
  EXPECT_EQ(d.kernel.stats().raw_points, before.raw_points);
}

TEST(RgKernel, AbsurdPoseRefused)
{
  Drive d;
  ScanInput s;
  s.scan_id = 9;
  s.utime = 5;
  s.map_from_base = geometry::Pose2(1e9, 0, 0);  // finite, so it passes the wire checks
  s.laser_points = {Vector2d(1, 0), Vector2d(1, 0.1)};
  EXPECT_FALSE(d.kernel.add_scan(s));
  EXPECT_EQ(d.kernel.map().regions().size(), 0u);
}

TEST(RgKernel, SameInputsSameMap)
{
  auto run = [] {
    Drive d;
    for (double x = 1.0; x < 3.9; x += 0.3) d.scan_at(geometry::Pose2(x, 1.5, 0.1));
    d.traverse_door(4.3, 0);
    for (double x = 4.5; x < 7.5; x += 0.3) d.scan_at(geometry::Pose2(x, 1.4, -0.1));
    return d.kernel.described_map();
  };
  const auto a = run(), b = run();
  ASSERT_EQ(a.regions().size(), b.regions().size());
  for (const auto& [id, r] : a.regions()) {
    EXPECT_EQ(r.segments.size(), b.region(id)->segments.size());
    EXPECT_EQ(r.freespace.bytes(), b.region(id)->freespace.bytes());
  }
}

}  // namespace
}  // namespace rgnav::rg_kernel
