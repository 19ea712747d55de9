#include <gtest/gtest.h>

#include "bus/typed.h"
#include "rgmap/rg_graph.h"
#include "rgmap/rg_map.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/rgmap_json.h"

namespace rgnav::rgmap {
namespace {

using Eigen::Vector2d;

// Two rooms joined by a door, plus a hallway joined to room 1 by a T-junction.
RgMap two_rooms_and_hallway()
{
  RgMap m;
  Region& r1 = m.add_region(geometry::Pose2(0, 0, 0), 100);
  r1.name = "office";
  r1.segments.push_back({Vector2d(0, 0), Vector2d(4, 0), 0.01, 120});
  r1.bbox_min = Vector2d(0, 0);
  r1.bbox_max = Vector2d(4, 3);
  r1.freespace = FreespaceBitmap(0.15, geometry::Pose2(0, 0, 0), 27, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 27; ++x) r1.freespace.set_free(x, y, true);
  Region& r2 = m.add_region(geometry::Pose2(5, 0, M_PI / 2), 200);
  Region& r3 = m.add_region(geometry::Pose2(0, 5, 0), 300);
  const int64_t id1 = r1.id, id2 = r2.id, id3 = r3.id;
  Gateway& door = m.add_gateway(GatewayClass::kDoor, id1, 200);
  door.gateway_points = {Vector2d(4, 1), Vector2d(4, 2)};
  door.crossing_points = {Vector2d(4, 1.5)};
  door.traversal_directions = {0.0};
  m.connect(door.id, id2, geometry::Pose2(5, 0, M_PI / 2));
  Gateway& t = m.add_gateway(GatewayClass::kTCrossing, id1, 300);
  t.crossing_points = {Vector2d(2, 3)};
  m.connect(t.id, id3, geometry::Pose2(0, 5, 0));
  m.current_region = id1;
  return m;
}

TEST(FreespaceBitmap, OneBitPerCellAndDissertationSize)
{
  // 30 m^2 at 15 cm: 6 m x 5 m = 40 x 34 cells = 1360 bits = 170 bytes (diss.: ~200 bytes).
  FreespaceBitmap b(0.15, geometry::Pose2(), 40, 34);
  EXPECT_EQ(b.bytes().size(), 170u);
  b.set_free(3, 2, true);
  EXPECT_TRUE(b.free(3, 2));
  EXPECT_FALSE(b.free(2, 3));
  EXPECT_EQ(b.free_cells(), 1);
  b.set_free(3, 2, false);
  EXPECT_EQ(b.free_cells(), 0);
}

TEST(FreespaceBitmap, FeaturesOfARotatedRectangle)
{
  // 4 m x 2 m free rectangle, grid rotated by 90 deg and placed at (10, 0).
  FreespaceBitmap b(0.1, geometry::Pose2(10, 0, M_PI / 2), 40, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 40; ++x) b.set_free(x, y, true);
  const auto f = b.features();
  EXPECT_NEAR(f.area, 8.0, 1e-9);
  EXPECT_NEAR(f.centroid.x(), 9.0, 1e-9);   // grid y (2 m wide) runs along -x after the rotation
  EXPECT_NEAR(f.centroid.y(), 2.0, 1e-9);
  // Uniform 4 m side: variance 4^2/12; main axis 2 sigma = 2 * sqrt(16/12).
  EXPECT_NEAR(f.main_axes.x(), 2 * std::sqrt(16.0 / 12 - 0.01 / 12), 1e-6);
  EXPECT_TRUE(b.is_free(Vector2d(9.5, 3.0)));
  EXPECT_FALSE(b.is_free(Vector2d(11.5, 3.0)));
}

TEST(FreespaceBitmap, CarveRayStopsBeforeTheHit)
{
  FreespaceBitmap b(0.1, geometry::Pose2(), 50, 10);
  b.carve_ray(Vector2d(0.05, 0.55), Vector2d(3.05, 0.55), true);
  EXPECT_TRUE(b.free(0, 5));
  EXPECT_TRUE(b.free(29, 5));
  EXPECT_FALSE(b.free(30, 5));  // the cell of the end point is an obstacle
  EXPECT_FALSE(b.free(10, 6));
}

TEST(RgMap, RegionNamesPickOneLiveRegionAndOutliveAMerge)
{
  auto m = two_rooms_and_hallway();   // region 1 is "office"
  std::string why;
  EXPECT_EQ(region_to_name(m, 2, "lab", &why), 2);
  EXPECT_TRUE(why.empty());
  EXPECT_EQ(region_to_name(m, 1, "office", &why), 1);   // its own name again
  EXPECT_EQ(region_to_name(m, 2, "Office", &why), 0);   // another region's, whatever the case
  EXPECT_NE(why.find("region 1"), std::string::npos) << why;
  EXPECT_EQ(region_to_name(m, 9, "lab", &why), 0);
  EXPECT_EQ(region_to_name(m, 2, "12", &why), 0);       // would read as an id
  EXPECT_EQ(region_to_name(m, 2, "lab ", &why), 0);
  EXPECT_EQ(region_to_name(m, 2, std::string(65, 'a'), &why), 0);
  EXPECT_EQ(region_to_name(m, 2, std::string("a\\b"), &why), 2);   // a backslash is printable
  EXPECT_EQ(region_to_name(m, 2, std::string("a") + char(9) + "b", &why), 0);
  // The hallway named, then found to be room 2 seen again: room 2 keeps the name, and the
  // hallway's id names room 2 from now on.
  m.region(3)->name = "hall";
  m.merge(3, 2, geometry::Pose2(1, 0, 0), 500);
  EXPECT_EQ(m.region(2)->name, "hall");
  EXPECT_EQ(region_to_name(m, 3, "lab", &why), 2);
}

TEST(RgMap, IdsNeverReusedAndConsistent)
{
  auto m = two_rooms_and_hallway();
  EXPECT_TRUE(m.consistency_problems().empty());
  EXPECT_EQ(m.add_region(geometry::Pose2(), 1).id, 4);
  EXPECT_THROW(m.insert_region(Region{}), std::invalid_argument);
  Region dup;
  dup.id = 2;
  EXPECT_THROW(m.insert_region(dup), std::invalid_argument);
}

TEST(RgMap, MergeNeutralizesGatewayWithOneRegionOnBothSides)
{
  // Diss. 6.1.1: the hallway (3) turns out to be the same place as room 2 seen again.
  auto m = two_rooms_and_hallway();
  Gateway& g = m.add_gateway(GatewayClass::kLTurn, 2, 400);
  g.crossing_points = {Vector2d(1, 1)};
  m.connect(g.id, 3, geometry::Pose2(1, 0, 0));
  EXPECT_FALSE(m.gateway(g.id)->neutralized);
  const int n = m.merge(3, 2, geometry::Pose2(1, 0, 0), 500);
  EXPECT_EQ(n, 1);
  EXPECT_TRUE(m.gateway(g.id)->neutralized);
  EXPECT_EQ(m.resolve(3), 2);
  EXPECT_EQ(m.region(3)->state, Region::State::kMerged);
  EXPECT_EQ(m.gateway(2)->region_b, 2);  // the T-junction now leads to region 2
  EXPECT_TRUE(m.consistency_problems().empty());
}

TEST(RgGraph, NodesPerSideAndShortestPath)
{
  const auto m = two_rooms_and_hallway();
  const RgGraph g = build_graph(m);
  // Door: 2 nodes (one per side), T-junction: 2 nodes. Region 1 holds one side of each.
  ASSERT_EQ(g.nodes.size(), 4u);
  int gateway_edges = 0, region_edges = 0;
  for (const auto& e : g.edges) (e.kind == GraphEdge::Kind::kGateway ? gateway_edges : region_edges)++;
  EXPECT_EQ(gateway_edges, 2);
  EXPECT_EQ(region_edges, 1);  // the two crossing points inside region 1
  // Door node in region 2 to T node in region 3: across the door, through region 1, across the T.
  int64_t door_in_2 = 0, t_in_3 = 0;
  for (const auto& n : g.nodes) {
    if (n.region_id == 2) door_in_2 = n.id;
    if (n.region_id == 3) t_in_3 = n.id;
  }
  const auto path = shortest_path(g, door_in_2, t_in_3);
  EXPECT_EQ(path.size(), 4u);
  // Crossing point of the door seen from region 2: (4, 1.5) in region 1 -> region 2 frame.
  for (const auto& n : g.nodes)
    if (n.id == door_in_2) {
      EXPECT_TRUE(n.point.isApprox(geometry::Pose2(5, 0, M_PI / 2).inverse() * Vector2d(4, 1.5)));
    }
}

TEST(RgMapConversions, LcmRoundTripValidatesAndPreserves)
{
  const auto m = two_rooms_and_hallway();
  const rg_map_t msg = to_msg(m);
  std::vector<uint8_t> buf;
  std::string why;
  ASSERT_TRUE(bus::encode(msg, &buf, &why)) << why;
  rg_map_t decoded;
  ASSERT_TRUE(bus::decode(buf.data(), buf.size(), &decoded, &why)) << why;
  const RgMap back = from_msg(decoded);
  // Structure is preserved exactly; float fields (sigma, resolution) are float on the wire,
  // so after one trip the map is a fixed point of the conversion.
  ASSERT_EQ(back.regions().size(), 3u);
  EXPECT_EQ(back.region(1)->name, "office");
  EXPECT_EQ(back.region(1)->freespace.bytes(), m.region(1)->freespace.bytes());
  EXPECT_EQ(back.gateway(1)->region_b, 2);
  EXPECT_EQ(back.gateway(2)->cls, GatewayClass::kTCrossing);
  EXPECT_NEAR(back.region(1)->segments[0].sigma, 0.01, 1e-7);
  EXPECT_EQ(to_json(from_msg(to_msg(back))).dump(), to_json(back).dump());
  const rg_graph_t gmsg = to_msg(build_graph(m), 5);
  ASSERT_TRUE(bus::encode(gmsg, &buf, &why)) << why;
}

TEST(RgMapJson, RoundTripAndRefusesCorruption)
{
  const auto m = two_rooms_and_hallway();
  const auto j = to_json(m);
  const RgMap back = from_json(nlohmann::json::parse(j.dump()));
  EXPECT_EQ(to_json(back).dump(), j.dump());
  EXPECT_EQ(back.next_region_id(), 4);

  auto bad = j;
  bad["gateways"][0]["region_a"] = 99;  // dangling gateway
  EXPECT_THROW(from_json(bad), std::invalid_argument);
  bad = j;
  bad["regions"][0]["freespace"]["bits_hex"] = "abc";
  EXPECT_THROW(from_json(bad), std::invalid_argument);
  bad = j;
  bad["regions"][0].erase("segments");
  try {
    from_json(bad);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("$.regions[0]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rgnav::rgmap
