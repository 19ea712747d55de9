// Metric functions of the RG map benchmark on hand-made cases with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "rgmap_metrics.h"

namespace rgnav::rgmap_pipeline {
namespace {

using Eigen::Vector2d;

// 10 x 4 cells: room 1 = x 0..4, room 2 = x 5..9 (all rows).
LabelGrid two_rooms()
{
  LabelGrid g(10, 4, 1.0, Vector2d(0, 0));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 10; ++x) g.at(x, y) = x < 5 ? 1 : 2;
  return g;
}

std::vector<int64_t> cells(const LabelGrid& g, int x0, int x1, int y0 = 0, int y1 = 3)
{
  std::vector<int64_t> out;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) out.push_back(static_cast<int64_t>(y) * g.width + x);
  return out;
}

TEST(Segmentation, PerfectRegionsScoreOne)
{
  const auto g = two_rooms();
  const auto s = score_segmentation(g, {{7, cells(g, 0, 4)}, {9, cells(g, 5, 9)}});
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_DOUBLE_EQ(s.recall, 1.0);
  EXPECT_DOUBLE_EQ(s.recall_full, 1.0);
  EXPECT_DOUBLE_EQ(s.jaccard, 1.0);
  EXPECT_DOUBLE_EQ(s.coverage, 1.0);
  EXPECT_EQ(s.over_segmented, 0);
  EXPECT_EQ(s.under_segmented, 0);
  EXPECT_EQ(s.region_to_room.at(7), 1);
  EXPECT_EQ(s.region_to_room.at(9), 2);
}

TEST(Segmentation, OneRegionOverTwoRoomsIsUnderSegmented)
{
  const auto g = two_rooms();
  const auto s = score_segmentation(g, {{1, cells(g, 0, 9)}});
  EXPECT_DOUBLE_EQ(s.precision, 0.5);   // best room holds half of the region
  EXPECT_DOUBLE_EQ(s.recall, 1.0);      // each room entirely inside it
  EXPECT_DOUBLE_EQ(s.jaccard, 0.5);     // 20 / 40 for either room
  EXPECT_EQ(s.under_segmented, 1);
  EXPECT_EQ(s.over_segmented, 0);
  EXPECT_EQ(s.region_to_room.at(1), 1);  // tie goes to the lower label
}

TEST(Segmentation, SplitRoomIsOverSegmentedAndPartialCoverageCounted)
{
  const auto g = two_rooms();
  // Room 1 split in two regions (x 0..1 and x 2..4); room 2 only half explored (x 5..9, y 0..1).
  const auto s = score_segmentation(g, {{1, cells(g, 0, 1)}, {2, cells(g, 2, 4)}, {3, cells(g, 5, 9, 0, 1)}});
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_DOUBLE_EQ(s.recall, (12.0 / 20.0 + 1.0) / 2.0);        // room 2: all of its explored part
  EXPECT_DOUBLE_EQ(s.recall_full, (12.0 / 20.0 + 10.0 / 20.0) / 2.0);
  EXPECT_DOUBLE_EQ(s.coverage, 30.0 / 40.0);
  EXPECT_EQ(s.over_segmented, 1);
  EXPECT_EQ(s.rooms_explored, 2);
}

TEST(Segmentation, RegionOutsideRoomsIsCountedNotScored)
{
  LabelGrid g = two_rooms();
  for (int x = 0; x < 10; ++x) g.at(x, 3) = 0;   // a wall row
  const auto s = score_segmentation(g, {{1, cells(g, 0, 4, 0, 2)}, {2, cells(g, 0, 9, 3, 3)}});
  EXPECT_EQ(s.regions_outside, 1);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_EQ(s.rooms_explored, 1);
}

TEST(Segmentation, SliversOfAtMostAQuarterSquareMetreAreLeftOutAsByBormann)
{
  // At 0.05 m a quarter square metre is 100 cells, the evaluation's limit for segments and rooms.
  LabelGrid g(40, 20, 0.05, Vector2d(0, 0));
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 40; ++x) g.at(x, y) = x < 30 ? 1 : 2;   // room 2: 10 x 20 = 200 cells
  for (int y = 0; y < 10; ++y) g.at(39, y) = 3;                  // room 3: 10 cells
  ASSERT_EQ(min_segment_cells(g), 100);
  RegionCells found{{1, cells(g, 0, 29, 0, 19)}, {2, cells(g, 28, 32, 0, 19)}, {3, cells(g, 33, 38, 0, 9)}};
  // Region 2 straddles rooms 1 and 2 with 100 cells: left out. Region 3 (60 cells) too.
  const RegionCells kept = without_small_regions(found, min_segment_cells(g));
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept.count(1), 1u);
  const LabelGrid rooms = without_small_rooms(g, min_segment_cells(g));
  EXPECT_EQ(rooms.at(39, 0), 0);
  EXPECT_EQ(rooms.at(35, 0), 2);
  const auto s = score_segmentation(rooms, kept);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_EQ(s.rooms, 2);
  // Scored whole, the straddling sliver costs precision.
  EXPECT_LT(score_segmentation(g, found).precision, 0.9);
}

TEST(Gateways, MatchedOneToOneNearestFirst)
{
  // Truth 0 and 1 both near found 0; found 0 is closer to truth 1, so truth 0 takes found 1.
  const std::vector<Vector2d> truth{{0, 0}, {1, 0}, {10, 10}};
  const std::vector<Vector2d> found{{0.8, 0}, {0.3, 0}, {5, 5}};
  const auto m = match_gateways(truth, found, 1.0);
  EXPECT_EQ(m.matched, 2);
  EXPECT_EQ(m.missed, 1);
  EXPECT_EQ(m.false_positives, 1);
  ASSERT_EQ(m.pairs.size(), 2u);
  EXPECT_EQ(m.pairs[0], std::make_pair(0, 1));
  EXPECT_EQ(m.pairs[1], std::make_pair(1, 0));
  EXPECT_NEAR(m.mean_error_m, (0.3 + 0.2) / 2, 1e-12);
}

TEST(Gateways, NothingMatchesBeyondTheDistance)
{
  const auto m = match_gateways({{0, 0}}, {{1.5, 0}}, 1.0);
  EXPECT_EQ(m.matched, 0);
  EXPECT_EQ(m.missed, 1);
  EXPECT_EQ(m.false_positives, 1);
}

Graph path(std::vector<int64_t> v)
{
  Graph g;
  for (size_t i = 0; i + 1 < v.size(); ++i) g.add_edge(v[i], v[i + 1]);
  return g;
}

TEST(Graphs, RelabelledGraphsAreIsomorphic)
{
  const Graph a = path({1, 2, 3, 4});
  const Graph b = path({40, 10, 30, 20});
  EXPECT_TRUE(isomorphic(a, b));
  Graph ca = a, cb = b;
  ca.add_edge(4, 1);
  cb.add_edge(20, 40);
  EXPECT_TRUE(isomorphic(ca, cb));
}

TEST(Graphs, SameCountsDifferentShapeIsNotIsomorphic)
{
  // Path of 4 vs star of 4: 4 nodes, 3 edges each.
  Graph star;
  star.add_edge(0, 1);
  star.add_edge(0, 2);
  star.add_edge(0, 3);
  EXPECT_FALSE(isomorphic(path({1, 2, 3, 4}), star));
  // Same degree sequence, not isomorphic: a 6-cycle vs two triangles (refinement cannot tell
  // them apart; the backtracking must).
  Graph hex = path({1, 2, 3, 4, 5, 6});
  hex.add_edge(6, 1);
  Graph tri;
  tri.add_edge(1, 2), tri.add_edge(2, 3), tri.add_edge(3, 1);
  tri.add_edge(4, 5), tri.add_edge(5, 6), tri.add_edge(6, 4);
  EXPECT_FALSE(isomorphic(hex, tri));
  EXPECT_FALSE(isomorphic(path({1, 2, 3}), path({1, 2, 3, 4})));
}

TEST(Graphs, ComparisonUnderTheRegionToRoomMapping)
{
  // Truth: hall 1 with rooms 2 and 3. Map: regions 10 (hall), 11 (hall again: over-segmented),
  // 12 (room 2); edges 10-11 (inside the hall), 11-12 (hall-room 2: right), 12-13 (13 unmapped).
  Graph truth;
  truth.add_edge(1, 2);
  truth.add_edge(1, 3);
  Graph map;
  map.add_edge(10, 11);
  map.add_edge(11, 12);
  map.add_edge(12, 13);
  const auto c = compare_graphs(truth, map, {{10, 1}, {11, 1}, {12, 2}});
  EXPECT_FALSE(c.isomorphic);
  EXPECT_EQ(c.edges_matched, 1);
  EXPECT_EQ(c.edges_missing, 1);
  EXPECT_EQ(c.edges_internal, 1);
  EXPECT_EQ(c.edges_extra, 1);
  EXPECT_EQ(c.rooms_unmatched, 1);
  EXPECT_EQ(c.map_nodes, 4);
  EXPECT_EQ(c.truth_edges, 2);
}

TEST(RegionGraph, NeutralizedAndOneSidedGatewaysAreNoEdges)
{
  rgmap::RgMap m;
  const int64_t a = m.add_region({}, 1).id;
  const int64_t b = m.add_region(geometry::Pose2(5, 0, 0), 2).id;
  const int64_t c = m.add_region(geometry::Pose2(10, 0, 0), 3).id;
  m.connect(m.add_gateway(rgmap::GatewayClass::kDoor, a, 4).id, b, geometry::Pose2(5, 0, 0));
  m.add_gateway(rgmap::GatewayClass::kDoor, b, 5);   // never traversed
  m.connect(m.add_gateway(rgmap::GatewayClass::kDoor, b, 6).id, c, geometry::Pose2(5, 0, 0));
  m.gateway(3)->neutralized = true;
  const Graph g = region_graph(m);
  EXPECT_EQ(g.nodes.size(), 3u);
  ASSERT_EQ(g.edges.size(), 1u);
  EXPECT_EQ(*g.edges.begin(), std::make_pair(a, b));
  const auto counts = count_map(m, 100);
  EXPECT_EQ(counts.gateways, 2);
  EXPECT_EQ(counts.neutralized, 1);
  EXPECT_EQ(counts.not_traversed, 1);
  EXPECT_EQ(counts.doors, 2);
}

// A T-crossing at x in [4, 6] joining regions 1 (west), 2 (east) and 3 (north): one gateway
// object per pair the robot went through, each with the crossing's outline in its region_a's frame.
struct TCrossingMap
{
  rgmap::RgMap m;
  const int64_t a = m.add_region({}, 1).id;
  const int64_t b = m.add_region(geometry::Pose2(7, 0, 0), 2).id;
  const int64_t c = m.add_region(geometry::Pose2(5, 3, M_PI / 2), 3).id;

  void went_through(int64_t from, int64_t to)
  {
    rgmap::Gateway& g = m.add_gateway(rgmap::GatewayClass::kTCrossing, from, 4);
    const geometry::Pose2 from_map = m.region(from)->map_from_region.inverse();
    for (const Vector2d& p : {Vector2d(4, 0), Vector2d(4, 2), Vector2d(6, 2), Vector2d(6, 0)}) g.gateway_points.push_back(from_map * p);
    m.connect(g.id, to, from_map * m.region(to)->map_from_region);
  }
};

TEST(RegionGraph, CrossingJoiningThreeRegionsIsThreeEdgesButOneGateway)
{
  TCrossingMap t;
  auto& m = t.m;
  t.went_through(t.a, t.b);
  t.went_through(t.b, t.c);
  t.went_through(t.c, t.a);
  EXPECT_EQ(region_graph(m).edges.size(), 3u);
  EXPECT_EQ(repeated_crossings(m), (std::set<int64_t>{2, 3}));
  EXPECT_EQ(count_map(m, 100).gateways, 1);
  ASSERT_EQ(gateway_positions(m).size(), 1u);
  EXPECT_NEAR((gateway_positions(m)[0] - Vector2d(5, 1)).norm(), 0.0, 1e-9);
  // Another crossing with a different outline is a gateway of its own.
  rgmap::Gateway& other = m.add_gateway(rgmap::GatewayClass::kTCrossing, t.a, 5);
  other.gateway_points = {{14, 0}, {14, 2}, {16, 2}, {16, 0}};
  EXPECT_EQ(count_map(m, 100).gateways, 2);
}

TEST(RegionGraph, CrossingJoinsEveryPairOfItsRegionsThoughTheRobotWentThroughTwo)
{
  // The robot went west -> east and east -> north through the crossing, never west -> north: the
  // crossing still joins west and north (as the truth's crossings join all their rooms).
  TCrossingMap t;
  t.went_through(t.a, t.b);
  t.went_through(t.b, t.c);
  const Graph g = region_graph(t.m);
  EXPECT_EQ(g.edges.size(), 3u);
  EXPECT_TRUE(g.edges.count({t.a, t.c}));
  // A door with the same regions elsewhere adds no pair the crossing does not have.
  t.m.connect(t.m.add_gateway(rgmap::GatewayClass::kDoor, t.a, 5).id, t.c,
              t.m.region(t.a)->map_from_region.inverse() * t.m.region(t.c)->map_from_region);
  EXPECT_EQ(region_graph(t.m).edges.size(), 3u);
}

TEST(RegionCells, FreespacePlacedThroughTheAlignment)
{
  // A region whose freespace is 2 x 1 cells of 1 m at region x 0..2, y 0..1; the region frame is
  // at map (1, 0) and the map frame at world (0, 1) rotated by 90 degrees.
  rgmap::RgMap m;
  auto& r = m.add_region(geometry::Pose2(1, 0, 0), 1);
  r.freespace = rgmap::FreespaceBitmap(1.0, geometry::Pose2(), 2, 1);
  r.freespace.set_free(0, 0, true);
  r.freespace.set_free(1, 0, true);
  LabelGrid grid(4, 4, 0.5, Vector2d(-2, 0));   // world x -2..0, y 0..2
  const auto out = region_cells(m, geometry::Pose2(0, 1, M_PI / 2), grid);
  // Region x 0..2 -> map x 1..3 -> world y 2..4 (above the grid but for its top row? no:
  // world y = 1 + map x, so map x 1..3 is world y 2..4: outside); map y 0..1 -> world x -1..0.
  EXPECT_TRUE(out.at(r.id).empty());
  LabelGrid tall(4, 10, 0.5, Vector2d(-2, 0));  // world y 0..5
  const auto in = region_cells(m, geometry::Pose2(0, 1, M_PI / 2), tall);
  // world x -1..0 -> columns 2, 3; world y 2..4 -> rows 4..7: 8 cells.
  ASSERT_EQ(in.at(r.id).size(), 8u);
  for (int64_t c : in.at(r.id)) {
    EXPECT_GE(c % 4, 2);
    EXPECT_GE(c / 4, 4);
    EXPECT_LE(c / 4, 7);
  }
}

// A region of w x h free cells of 0.5 m at `map_from_region`.
rgmap::Region& free_block(rgmap::RgMap& m, const geometry::Pose2& map_from_region, int w, int h)
{
  auto& r = m.add_region(map_from_region, 1);
  r.freespace = rgmap::FreespaceBitmap(0.5, geometry::Pose2(), w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) r.freespace.set_free(x, y, true);
  return r;
}

TEST(OverlappingRegions, OnePlaceMappedTwiceIsAPairNeighboursAreNot)
{
  rgmap::RgMap m;
  free_block(m, geometry::Pose2(), 8, 8);                 // a 4 x 4 m room at map (0..4, 0..4)
  free_block(m, geometry::Pose2(4, 0, 0), 8, 8);          // the room east of it
  EXPECT_EQ(overlapping_region_pairs(m), 0);
  // A region that saw 1 m into its neighbour (a quarter of it): still none.
  free_block(m, geometry::Pose2(8, 0, 0), 8, 8).freespace = [] {
    rgmap::FreespaceBitmap f(0.5, geometry::Pose2(-1, 0, 0), 10, 8);   // region x -1..4
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 10; ++x) f.set_free(x, y, true);
    return f;
  }();
  EXPECT_EQ(overlapping_region_pairs(m), 0);
  // The first room again as a region of its own, in another frame (rotated by 90 degrees).
  auto& again = free_block(m, geometry::Pose2(4, 0, M_PI / 2), 8, 7);
  EXPECT_EQ(overlapping_region_pairs(m), 1);
  EXPECT_EQ(count_map(m, 100).overlapping_regions, 1);
  again.state = rgmap::Region::State::kMerged;   // merged away: no region of the map
  EXPECT_EQ(overlapping_region_pairs(m), 0);
}

TEST(FitRigid, RecoversAKnownTransform)
{
  const geometry::Pose2 t(3, -2, 0.7);
  std::vector<Vector2d> a{{0, 0}, {1, 0}, {0, 2}, {5, 5}}, b;
  for (const auto& p : a) b.push_back(t * p);
  const auto f = fit_rigid(a, b);
  EXPECT_NEAR(f.x(), 3, 1e-9);
  EXPECT_NEAR(f.y(), -2, 1e-9);
  EXPECT_NEAR(f.theta(), 0.7, 1e-9);
}

}  // namespace
}  // namespace rgnav::rgmap_pipeline
