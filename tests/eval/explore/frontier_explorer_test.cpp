#include "frontier_explorer.h"

#include <gtest/gtest.h>

namespace rgnav::explore_eval {
namespace {

using plan_eval::OccupancyGrid;

// A 10 x 10 free block in unknown space, walled on three sides, open at x = 14 (its right side).
OccupancyGrid room_open_right()
{
  OccupancyGrid g(0.1, Eigen::Vector2d::Zero(), 20, 20);
  for (int y = 5; y < 15; ++y)
    for (int x = 5; x < 15; ++x) g.set(Cell(x, y), OccupancyGrid::kFree);
  for (int k = 4; k <= 15; ++k) {
    g.set(Cell(4, k), OccupancyGrid::kOccupied);
    g.set(Cell(k, 4), OccupancyGrid::kOccupied);
    g.set(Cell(k, 15), OccupancyGrid::kOccupied);
  }
  return g;
}

TEST(FrontierClusters, TheOpenSideIsOneFrontier)
{
  const auto clusters = find_frontier_clusters(room_open_right(), 6);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].cells.size(), 10u);
  for (const auto& c : clusters[0].cells) EXPECT_EQ(c.x(), 14);
  EXPECT_NEAR(clusters[0].centroid.x(), 1.45, 1e-9);
  EXPECT_NEAR(clusters[0].centroid.y(), 1.0, 1e-9);
}

TEST(FrontierClusters, NarrowerThanTheRobotIsNone)
{
  auto g = room_open_right();
  for (int y = 5; y < 15; ++y)
    if (y < 9 || y > 11) g.set(Cell(15, y), OccupancyGrid::kOccupied);   // a 3-cell gap left open
  EXPECT_EQ(find_frontier_clusters(g, 6).size(), 0u);
  EXPECT_EQ(find_frontier_clusters(g, 3).size(), 1u);
}

TEST(ScanGrid, BeamsFreeTheirCellsAndMarkTheirEnds)
{
  ScanGrid grid(0.1, 5.0);
  sensors::LaserScan s;
  s.angle_min = -0.1;
  s.angle_increment = 0.1;
  s.range_min = 0.05;
  s.range_max = 8.183;
  s.ranges = {2.0f, 2.0f, 8.183f};   // two hits 2 m ahead, one no return
  const geometry::Pose2 base(0.05, 0.05, 0.0);
  grid.add_scan(base, geometry::Pose2(), s, 3.0, 0.2);
  const auto& geo = grid.geometry();
  EXPECT_EQ(grid.state(geo.cell_of({1.0, 0.05})), OccupancyGrid::kFree);
  EXPECT_EQ(grid.state(geo.cell_of({2.05, 0.05})), OccupancyGrid::kOccupied);
  EXPECT_EQ(grid.state(geo.cell_of({-0.1, 0.05})), OccupancyGrid::kFree);        // the robot's footprint
  EXPECT_EQ(grid.state(geo.cell_of({-1.0, 0.05})), OccupancyGrid::kUnknown);     // behind it
  // The no return beam (0.1 rad left) is free up to max_range, nothing marked at its end.
  const Eigen::Vector2d far = base.translation() + 2.9 * Eigen::Vector2d(std::cos(0.1), std::sin(0.1));
  EXPECT_EQ(grid.state(geo.cell_of(far)), OccupancyGrid::kFree);
  const auto crop = grid.cropped(2, OccupancyGrid::kUnknown);
  EXPECT_GT(crop.width, 30);
  EXPECT_LT(crop.width, 40);
}

}  // namespace
}  // namespace rgnav::explore_eval
