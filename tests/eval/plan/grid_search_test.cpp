// The planning benchmark's yardsticks (grid_search.h, occupancy_grid.h): the reference shortest
// path is the straight line where nothing is in the way, goes round a wall keeping the robot
// radius, and finds nothing through a closed wall; the whole-building grid is composed in the
// map frame through each region's map_from_region.
#include <gtest/gtest.h>

#include <cmath>

#include "grid_search.h"
#include "occupancy_grid.h"

namespace rgnav::plan_eval {
namespace {

using Eigen::Vector2d;

constexpr double kRadius = 0.26;

// A w x h metre room at 0.05 m: free inside, its outline occupied.
OccupancyGrid room(double w, double h)
{
  OccupancyGrid g(0.05, Vector2d(-0.5, -0.5), static_cast<int>((w + 1.0) / 0.05), static_cast<int>((h + 1.0) / 0.05));
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const Vector2d p = g.center_of(Cell(x, y));
      if (p.x() > 0 && p.y() > 0 && p.x() < w && p.y() < h) g.set(Cell(x, y), OccupancyGrid::kFree);
    }
  g.draw_occupied({0, 0}, {w, 0});
  g.draw_occupied({w, 0}, {w, h});
  g.draw_occupied({w, h}, {0, h});
  g.draw_occupied({0, h}, {0, 0});
  return g;
}

// The smallest clearance along the path, sampled every 1 cm.
double path_clearance(const ConfigSpace& cs, const std::vector<Vector2d>& pts)
{
  double m = 1e9;
  for (size_t k = 1; k < pts.size(); ++k) {
    const int n = std::max(1, static_cast<int>((pts[k] - pts[k - 1]).norm() / 0.01));
    for (int i = 0; i <= n; ++i) m = std::min(m, cs.clearance_at(pts[k - 1] + (pts[k] - pts[k - 1]) * (double(i) / n)));
  }
  return m;
}

TEST(ReferencePath, StraightLineInAnEmptyRoom)
{
  const ConfigSpace cs(room(10, 8), kRadius);
  GridSearch search(cs);
  const Vector2d a(2.0, 2.0), b(8.0, 6.0);
  const auto p = search.shortest(a, b, 0.6);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->length, (b - a).norm(), 0.005 * (b - a).norm());
  EXPECT_EQ(p->points.front(), a);
  EXPECT_EQ(p->points.back(), b);
  EXPECT_LE(p->points.size(), 3u);
  // The baseline's 8-connected path is longer but never shorter than the straight line.
  const auto q = search.wall_cost_astar(a, b, 0.6, WallCost{});
  ASSERT_TRUE(q);
  EXPECT_GE(q->length, (b - a).norm() - 1e-9);
  EXPECT_GT(q->length, p->length + 0.1);
}

TEST(ReferencePath, GoesRoundAWallKeepingTheRobotRadius)
{
  OccupancyGrid g = room(10, 8);
  g.draw_occupied({5, 0}, {5, 6});   // a wall from the bottom to 2 m below the top
  const ConfigSpace cs(std::move(g), kRadius);
  GridSearch search(cs);
  const Vector2d a(2.0, 2.0), b(8.0, 2.0);
  const auto p = search.shortest(a, b, 0.6);
  ASSERT_TRUE(p);
  // Round the wall's end, at least a radius from it: twice |(3, 4.26)| = 10.42 m (the grid
  // adds up to a cell's diagonal to the radius at the end of the wall).
  const double expected = 2.0 * std::hypot(3.0, 4.0 + kRadius);
  EXPECT_GT(p->length, expected - 0.05);
  EXPECT_LT(p->length, expected + 0.2);
  EXPECT_GE(path_clearance(cs, p->points), kRadius - 1e-6);
  EXPECT_TRUE(search.connected(a, b, 0.6));
  const auto q = search.wall_cost_astar(a, b, 0.6, WallCost{});
  ASSERT_TRUE(q);
  EXPECT_GE(q->length, p->length);
}

TEST(ReferencePath, NoPathThroughAClosedWall)
{
  OccupancyGrid g = room(10, 8);
  g.draw_occupied({5, 0}, {5, 8});
  const ConfigSpace cs(std::move(g), kRadius);
  GridSearch search(cs);
  EXPECT_FALSE(search.shortest({2, 2}, {8, 2}, 0.6));
  EXPECT_FALSE(search.wall_cost_astar({2, 2}, {8, 2}, 0.6, WallCost{}));
  EXPECT_FALSE(search.connected({2, 2}, {8, 2}, 0.6));
  // A gap narrower than the robot is closed too: 0.4 m < 2 x 0.26 m.
  OccupancyGrid h = room(10, 8);
  h.draw_occupied({5, 0}, {5, 3.8});
  h.draw_occupied({5, 4.2}, {5, 8});
  const ConfigSpace cs2(std::move(h), kRadius);
  GridSearch search2(cs2);
  EXPECT_FALSE(search2.shortest({2, 2}, {8, 2}, 0.6));
}

TEST(ReferencePath, StartOnAWallIsMovedOffItWithinTheAdaptDistance)
{
  const ConfigSpace cs(room(10, 8), kRadius);
  GridSearch search(cs);
  const auto p = search.shortest({0.1, 4.0}, {5.0, 4.0}, 0.6);
  ASSERT_TRUE(p);
  EXPECT_GE(cs.clearance_at(p->points.front()), kRadius);
  EXPECT_FALSE(search.shortest({0.1, 4.0}, {5.0, 4.0}, 0.05));
}

TEST(ComposeOccupancy, PlacesRegionsThroughMapFromRegion)
{
  rgmap::RgMap map;
  // A 4 x 3 m region whose frame is 10 m east of and turned 90 degrees from the map's.
  auto& r = map.add_region(geometry::Pose2(10.0, 0.0, M_PI / 2), 0);
  r.freespace = rgmap::FreespaceBitmap(0.1, geometry::Pose2(), 40, 30);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) r.freespace.set_free(x, y, true);
  r.segments.push_back({Vector2d(0, 1.5), Vector2d(4, 1.5), 0, 0});
  const OccupancyGrid g = compose_occupancy(map, 0.05);
  // Region (1, 0.5) lies at map (9.5, 1); region (1, 1.5) on the segment at map (8.5, 1).
  EXPECT_EQ(g.at(g.cell_of({9.5, 1.0})), OccupancyGrid::kFree);
  EXPECT_EQ(g.at(g.cell_of({8.5, 1.0})), OccupancyGrid::kOccupied);
  EXPECT_EQ(g.at(g.cell_of({10.5, 1.0})), OccupancyGrid::kUnknown);   // region y < 0
  EXPECT_EQ(g.at(g.cell_of({9.5, 4.5})), OccupancyGrid::kUnknown);    // region x > 4
}

// A door whose opening the region's freespace leaves out (the RG kernel trims freespace at narrow
// passages): only the gateway's carved opening lets the reference through, as it lets rgnav's
// planner.
TEST(ComposeOccupancy, GatewayOpeningsAreFreeAsThePlannerCarvesThem)
{
  rgmap::RgMap map;
  auto& r = map.add_region(geometry::Pose2(), 0);
  r.freespace = rgmap::FreespaceBitmap(0.1, geometry::Pose2(), 100, 40);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 100; ++x) r.freespace.set_free(x, y, x < 48 || x >= 52);
  r.segments.push_back({Vector2d(5, 0), Vector2d(5, 1.5), 0, 0});
  r.segments.push_back({Vector2d(5, 2.5), Vector2d(5, 4), 0, 0});
  auto& door = map.add_gateway(rgmap::GatewayClass::kDoor, r.id, 0);
  door.gateway_points = {Vector2d(5, 1.5), Vector2d(5, 2.5)};
  door.crossing_points = {Vector2d(5, 2)};

  const ConfigSpace trimmed(compose_occupancy(map, 0.05, 0.0), kRadius);
  GridSearch no_carve(trimmed);
  EXPECT_FALSE(no_carve.shortest({2, 2}, {8, 2}, 0.6));

  const ConfigSpace carved(compose_occupancy(map, 0.05, 0.5), kRadius);
  GridSearch search(carved);
  const auto p = search.shortest({2, 2}, {8, 2}, 0.6);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->length, 6.0, 0.03);
  // The walls beside the opening stay: nothing passes at y = 1.
  EXPECT_FALSE(carved.line_free({4, 1}, {6, 1}));
}

}  // namespace
}  // namespace rgnav::plan_eval
