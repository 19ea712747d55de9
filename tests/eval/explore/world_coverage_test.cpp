#include "world_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rgnav::explore_eval {
namespace {

using Eigen::Vector2d;

Raster raster(int w, int h, double res)
{
  Raster r;
  r.width = w;
  r.height = h;
  r.resolution = res;
  return r;
}

// Clearance of a w x h m box room with walls on its edges (cells' distance to the nearest edge).
std::vector<float> box_clearance(const Raster& r)
{
  std::vector<float> c(static_cast<size_t>(r.size()));
  const double w = r.width * r.resolution, h = r.height * r.resolution;
  for (int64_t i = 0; i < r.size(); ++i) {
    const Vector2d p = r.center(i);
    c[static_cast<size_t>(i)] = static_cast<float>(std::min({p.x(), p.y(), w - p.x(), h - p.y()}));
  }
  return c;
}

TEST(TraceRay, VisitsTheCellsInOrderUpToTheEnd)
{
  const Raster r = raster(10, 10, 0.1);
  std::vector<int64_t> cells;
  trace_ray(r, Vector2d(0.05, 0.05), Vector2d(0.95, 0.05), [&](int64_t i) { cells.push_back(i); });
  ASSERT_EQ(cells.size(), 10u);
  for (int64_t k = 0; k < 10; ++k) EXPECT_EQ(cells[static_cast<size_t>(k)], k);
}

TEST(TraceRay, DiagonalEndsInTheEndCellAndLeavesNoGap)
{
  const Raster r = raster(10, 10, 0.1);
  std::vector<int64_t> cells;
  trace_ray(r, Vector2d(0.05, 0.05), Vector2d(0.73, 0.42), [&](int64_t i) { cells.push_back(i); });
  ASSERT_FALSE(cells.empty());
  EXPECT_EQ(cells.front(), r.index(0, 0));
  EXPECT_EQ(cells.back(), r.index(7, 4));
  EXPECT_EQ(cells.size(), 7u + 4u + 1u);
  for (size_t k = 1; k < cells.size(); ++k) {
    const int64_t a = cells[k - 1], b = cells[k];
    EXPECT_EQ(std::abs(a % 10 - b % 10) + std::abs(a / 10 - b / 10), 1) << "step " << k;   // 4-neighbours
  }
}

TEST(TraceRay, ClipsToTheRaster)
{
  const Raster r = raster(10, 10, 0.1);
  int inside = 0;
  trace_ray(r, Vector2d(0.55, 0.55), Vector2d(5.0, 0.55), [&](int64_t i) {
    EXPECT_GE(i, 0);
    ++inside;
  });
  EXPECT_EQ(inside, 5);
}

TEST(ReachableArea, IsTheRoomLessWhatTheBodyCannotReach)
{
  const Raster r = raster(80, 40, 0.05);   // 4 x 2 m
  const auto c = box_clearance(r);
  const auto a = reachable_area(r, c, Vector2d(2.0, 1.0), 0.25, 0.05);
  ASSERT_TRUE(a);
  // Centres more than 0.3 m from the walls stand; widened by 0.25 m the body sweeps all but a
  // 0.05 m band along the walls (3.9 x 1.9 m), corners rounded.
  EXPECT_NEAR(a->free_m2, 3.9 * 1.9, 0.15);
  EXPECT_NEAR(static_cast<double>(a->stand_cells) * 0.05 * 0.05, 3.4 * 1.4, 0.15);
  EXPECT_FALSE(a->free[static_cast<size_t>(r.index(0, 20))]);    // at the wall
  EXPECT_TRUE(a->free[static_cast<size_t>(r.index(2, 20))]);     // 0.125 m from it: the body reaches
}

TEST(ReachableArea, NoneFromInsideAWallAndOnlyTheStartsSide)
{
  Raster r = raster(80, 40, 0.05);
  auto c = box_clearance(r);
  // A start where the body does not fit goes to the nearest place within 0.5 m where it does.
  EXPECT_TRUE(reachable_area(r, c, Vector2d(0.1, 0.1), 0.25, 0.05));
  EXPECT_FALSE(reachable_area(r, c, Vector2d(-0.5, -0.5), 0.25, 0.05));
  // A wall across the room at x = 2 m: only the start's half.
  for (int64_t i = 0; i < r.size(); ++i)
    c[static_cast<size_t>(i)] = std::min(c[static_cast<size_t>(i)], static_cast<float>(std::abs(r.center(i).x() - 2.0)));
  const auto a = reachable_area(r, c, Vector2d(1.0, 1.0), 0.25, 0.05);
  ASSERT_TRUE(a);
  EXPECT_NEAR(a->free_m2, 1.9 * 1.9, 0.1);
  EXPECT_FALSE(a->free[static_cast<size_t>(r.index(60, 20))]);
}

TEST(SeenArea, CountsBeamCellsOfTheCountedAreaOnce)
{
  const Raster r = raster(100, 20, 0.1);   // 10 x 2 m
  std::vector<uint8_t> counted(static_cast<size_t>(r.size()), 0);
  for (int x = 0; x < 100; ++x) counted[static_cast<size_t>(r.index(x, 10))] = 1;   // one row
  SeenArea seen(r, counted);
  EXPECT_EQ(seen.counted_cells(), 100);
  sensors::LaserScan s;
  s.angle_min = 0;
  s.angle_increment = 0.1;
  s.range_min = 0.05;
  s.range_max = 8.183;
  s.ranges = {3.0f};   // a hit 3 m ahead along the row
  const geometry::Pose2 laser(0.05, 1.05, 0.0);
  seen.add_scan(laser, s, 8.0);
  EXPECT_EQ(seen.seen_counted_cells(), 31);   // cells 0..30 (the hit's cell included)
  seen.add_scan(laser, s, 8.0);
  EXPECT_EQ(seen.seen_counted_cells(), 31);
  s.ranges = {8.183f};   // no return: seen up to max_range
  seen.add_scan(laser, s, 8.0);
  EXPECT_EQ(seen.seen_counted_cells(), 81);
  EXPECT_NEAR(seen.ratio(), 0.81, 1e-9);
  s.ranges = {0.0f};     // invalid: nothing
  seen.add_scan(geometry::Pose2(9.95, 1.05, M_PI), s, 8.0);
  EXPECT_EQ(seen.seen_counted_cells(), 81);
}

}  // namespace
}  // namespace rgnav::explore_eval
