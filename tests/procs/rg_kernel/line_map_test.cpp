#include <gtest/gtest.h>

#include <random>

#include "procs/rg_kernel/line_map.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;
using rgmap::LineSegment;

TEST(ExtractSegments, CornerGivesTwoSegments)
{
  std::vector<Vector2d> pts;
  for (int i = 0; i <= 20; ++i) pts.emplace_back(2.0, -1.0 + 0.1 * i);   // x = 2 from y -1 to 1
  for (int i = 1; i <= 20; ++i) pts.emplace_back(2.0 - 0.1 * i, 1.0);    // then y = 1 back to x 0
  const auto segs = extract_segments(pts, {});
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_NEAR(segs[0].a.x(), 2.0, 1e-9);
  EXPECT_NEAR(std::fabs(segs[0].b.y() - segs[0].a.y()), 2.0, 0.05);
  EXPECT_NEAR(segs[1].a.y(), 1.0, 0.02);
}

TEST(ExtractSegments, GapSplitsAndShortPiecesDropped)
{
  std::vector<Vector2d> pts;
  for (int i = 0; i < 10; ++i) pts.emplace_back(0.1 * i, 1.0);
  for (int i = 0; i < 10; ++i) pts.emplace_back(3.0 + 0.1 * i, 1.0);  // 2.1 m jump
  pts.emplace_back(5, 5);
  pts.emplace_back(5.01, 5);  // two points: no segment
  EXPECT_EQ(extract_segments(pts, {}).size(), 2u);
}

TEST(MergeSegments, DissertationParameters)
{
  const MergeOptions o;  // 3 deg, 20 mm, 150 mm
  // Collinear with a 10 cm gap: merged, spanning the farthest end points.
  auto m = merge_segments({{Vector2d(0, 0), Vector2d(1, 0), 0, 10}, {Vector2d(1.1, 0.005), Vector2d(2, 0.005), 0, 10}}, o);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR((m[0].b - m[0].a).norm(), 2.0, 0.01);
  EXPECT_EQ(m[0].support, 20);
  // Gap of 20 cm: kept apart.
  EXPECT_EQ(merge_segments({{Vector2d(0, 0), Vector2d(1, 0), 0, 1}, {Vector2d(1.2, 0), Vector2d(2, 0), 0, 1}}, o).size(), 2u);
  // Parallel 5 cm apart (D_L > 20 mm): kept apart.
  EXPECT_EQ(merge_segments({{Vector2d(0, 0), Vector2d(1, 0), 0, 1}, {Vector2d(0, 0.05), Vector2d(1, 0.05), 0, 1}}, o).size(), 2u);
  // 5 degrees apart: kept apart.
  EXPECT_EQ(merge_segments({{Vector2d(0, 0), Vector2d(1, 0), 0, 1},
                            {Vector2d(0.5, 0), Vector2d(0.5 + std::cos(0.0873), std::sin(0.0873)), 0, 1}}, o).size(), 2u);
  // Lines near angle pi / 0 (wrap-around) merge too.
  EXPECT_EQ(merge_segments({{Vector2d(0, 0), Vector2d(1, 0.001), 0, 1}, {Vector2d(2, 0), Vector2d(1, 0.001), 0, 1}}, o).size(), 1u);
}

TEST(MergeSegments, ThirtyScansCompressLikeFigure54)
{
  // Diss. Fig. 5.4: ~5000 points from 30 scans -> ~40 segments (factor ~50).
  const auto walls = testing::two_rooms();
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<LineSegment> map;
  int64_t points = 0;
  for (int k = 0; k < 30; ++k) {
    const geometry::Pose2 pose(0.5 + 0.1 * k, 1.5, 0.2 * std::sin(k));
    auto pts = testing::cast(walls, pose);
    for (auto& p : pts) p = pose * Vector2d(p.x() + noise(rng), p.y() + noise(rng));
    points += static_cast<int64_t>(pts.size());
    auto segs = extract_segments(pts, {});
    map.insert(map.end(), segs.begin(), segs.end());
    map = merge_segments(std::move(map), {});
  }
  const double compression = static_cast<double>(points) / (2.0 * map.size());
  EXPECT_LE(map.size(), 40u);
  EXPECT_GE(compression, 50.0) << map.size() << " segments from " << points << " points";
}

}  // namespace
}  // namespace rgnav::rg_kernel
