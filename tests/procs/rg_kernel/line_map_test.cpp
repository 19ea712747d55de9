#include <gtest/gtest.h>

#include <random>

#include "geometry/symmetric_eigen2.h"
#include "procs/rg_kernel/line_map.h"
#include "procs/rg_kernel/line_map_fidelity.h"
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

// Scans of two_rooms() from 30 poses with range noise (Gaussian sigma, then rounded to `step`
// like a log that stores ranges coarsely), merged scan by scan as the region builder does.
struct MergedRun
{
  std::vector<LineSegment> map;
  std::vector<Vector2d> points;   // every end point, region frame
};

MergedRun merge_thirty_scans(double sigma, double step, bool noise_aware, uint32_t seed)
{
  const auto walls = testing::two_rooms();
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  MergedRun run;
  for (int k = 0; k < 30; ++k) {
    const geometry::Pose2 pose(0.5 + 0.1 * k, 1.5, 0.2 * std::sin(k));
    std::vector<Vector2d> pts;
    for (const auto& p : testing::cast(walls, pose)) {
      double r = p.norm() + noise(rng);
      if (step > 0) r = step * std::round(r / step);
      pts.push_back(pose * Vector2d(p.normalized() * r));
    }
    const double sigma_scan = noise_aware ? estimate_range_noise(pts, ExtractOptions{}.max_point_gap) : 0.0;
    run.map = merge_into(std::move(run.map), extract_segments(pts, {}, sigma_scan), {}, sigma_scan);
    run.points.insert(run.points.end(), pts.begin(), pts.end());
  }
  return run;
}

TEST(MergeSegments, ShortNoisySegmentJoinsTheLongWallItLiesOn)
{
  // A 4 m wall and a 0.3 m piece of it seen 4 mm off and tilted by 2.5 deg (a few points at
  // range: its direction is uncertain). The dissertation's D_L measures the long segment's end
  // points against the short one's extended line (8.7 cm here) and refuses; against their
  // common line both lie within D_L^max.
  const double tilt = 2.5 * M_PI / 180;
  const LineSegment wall{Vector2d(0, 0), Vector2d(4, 0), 0.005, 200};
  const Vector2d c(2.0, 0.004), u(std::cos(tilt), std::sin(tilt));
  const LineSegment piece{c - 0.15 * u, c + 0.15 * u, 0.005, 6};
  EXPECT_GT(line_distance(wall, piece), MergeOptions{}.dl_max);
  const auto m = merge_into({wall}, {piece}, {});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].support, 206);
  // The result stays on the well-supported wall: the 6-point piece moves it by a fraction of a mm.
  EXPECT_LT(std::fabs(m[0].a.y()), 0.001);
  EXPECT_LT(std::fabs(m[0].b.y()), 0.001);
  EXPECT_NEAR((m[0].b - m[0].a).norm(), 4.0, 0.001);
}

TEST(MergeSegments, MergedSegmentIsTheTotalLeastSquaresLineOfTheirPoints)
{
  // Two observations of one wall 1.5 cm apart, one with 9x the points. The merged segment lies
  // on the total least squares line of all the points behind both (here known exactly), not on
  // the two farthest end points (from (0, 0) to (3, 0.015)).
  std::vector<Vector2d> pts;
  for (int i = 0; i < 90; ++i) pts.emplace_back(2.0 * i / 89.0, (i % 2 ? 0.004 : -0.004));
  for (int i = 0; i < 10; ++i) pts.emplace_back(1.0 + 2.0 * i / 9.0, 0.015 + (i % 2 ? 0.004 : -0.004));
  const LineSegment heavy{Vector2d(0, 0), Vector2d(2, 0), 0.004, 90};
  const LineSegment light{Vector2d(1.0, 0.015), Vector2d(3, 0.015), 0.004, 10};
  const auto m = merge_segments({heavy, light}, {});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].support, 100);
  Vector2d c = Vector2d::Zero();
  for (const auto& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - c) * (p - c).transpose();
  const Vector2d normal = geometry::symmetric_eigen(cov).vectors.col(0);
  // Evenly spaced points vs the model's uniform spread: agreement to a fraction of a mm.
  EXPECT_LT(std::fabs(normal.dot(m[0].a - c)), 0.0005);
  EXPECT_LT(std::fabs(normal.dot(m[0].b - c)), 0.0005);
  EXPECT_NEAR((m[0].b - m[0].a).norm(), 3.0, 0.002);
  // Its spread says that the points behind it disagree by more than either observation's own.
  EXPECT_GT(m[0].sigma, 0.004);
}

TEST(MergeSegments, ParallelWallsStayApartAfterManyMerges)
{
  // Both faces of furniture 6 cm in front of a wall, each observed 20 times with small offsets:
  // averaging must not drag the two lines together.
  std::mt19937 rng(3);
  std::normal_distribution<double> off(0.0, 0.003);
  std::vector<LineSegment> map;
  for (int k = 0; k < 20; ++k) {
    const double x0 = 0.1 * k;
    map = merge_into(std::move(map), {{Vector2d(x0, off(rng)), Vector2d(x0 + 1.0, off(rng)), 0.004, 20}}, {});
    map = merge_into(std::move(map), {{Vector2d(x0, 0.06 + off(rng)), Vector2d(x0 + 1.0, 0.06 + off(rng)), 0.004, 20}}, {});
  }
  ASSERT_EQ(map.size(), 2u);
  const double y0 = 0.5 * (map[0].a.y() + map[0].b.y()), y1 = 0.5 * (map[1].a.y() + map[1].b.y());
  EXPECT_NEAR(std::fabs(y0 - y1), 0.06, 0.005);
}

TEST(MergeSegments, NoiseRaisesTheDistanceToleranceOnly)
{
  const LineSegment a{Vector2d(0, 0), Vector2d(1, 0), 0.01, 20};
  const LineSegment b{Vector2d(0.5, 0.04), Vector2d(1.5, 0.04), 0.01, 20};
  EXPECT_EQ(merge_segments({a, b}, {}).size(), 2u);                // 4 cm > 20 mm
  EXPECT_EQ(merge_segments({a, b}, {}, 0.015).size(), 1u);         // range noise 1.5 cm: 3 sigma = 4.5 cm
  MergeOptions off;
  off.noise_dl_factor = 0;
  EXPECT_EQ(merge_segments({a, b}, off, 0.015).size(), 2u);        // factor 0: D_L^max alone
  const LineSegment far{Vector2d(0.5, 0.2), Vector2d(1.5, 0.2), 0.01, 20};
  EXPECT_EQ(merge_segments({a, far}, {}, 0.015).size(), 2u);       // 20 cm: separate walls
}

TEST(RangeNoise, EstimatesTheSigmaOfTheScan)
{
  const auto walls = testing::two_rooms();
  const geometry::Pose2 pose(1.5, 1.5, 0.3);
  const auto clean = testing::cast(walls, pose);
  std::vector<Vector2d> exact;
  for (const auto& p : clean) exact.push_back(pose * p);
  EXPECT_LT(estimate_range_noise(exact, 0.25), 0.001);
  for (const double sigma : {0.005, 0.015}) {
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<Vector2d> noisy;
    for (const auto& p : clean) noisy.push_back(pose * Vector2d(p.normalized() * (p.norm() + noise(rng))));
    EXPECT_NEAR(estimate_range_noise(noisy, 0.25), sigma, 0.3 * sigma) << sigma;
  }
  // Too few neighbouring triples: no estimate.
  EXPECT_EQ(estimate_range_noise({Vector2d(0, 0), Vector2d(0.1, 0), Vector2d(0.2, 0.01)}, 0.25), 0.0);
}

TEST(MergeSegments, CoarseRangesCompressOnlyWithNoiseAwareTolerances)
{
  // Ranges stored in 5 cm steps (as in the ACES log): the dissertation's fixed 30 mm split and
  // 20 mm D_L^max cut walls into staircases and keep observations apart; tolerances that follow
  // the estimated range noise give a compact map that still explains the points.
  const MergedRun fixed = merge_thirty_scans(0.003, 0.05, false, 5);
  const MergedRun aware = merge_thirty_scans(0.003, 0.05, true, 5);
  EXPECT_LT(aware.map.size(), fixed.map.size()) << aware.map.size() << " vs " << fixed.map.size();
  const double compression = static_cast<double>(aware.points.size()) / (2.0 * aware.map.size());
  EXPECT_GE(compression, 50.0) << aware.map.size() << " segments";
  const LineMapFidelity f = measure_fidelity(aware.points, aware.map);
  EXPECT_GT(f.explained_share(), 0.95);
  EXPECT_LT(f.mean_distance(), 0.03);
  // Fine ranges: the noise-aware tolerances stay at the dissertation's values.
  const MergedRun fine = merge_thirty_scans(0.003, 0.0, true, 5);
  const MergedRun fine_fixed = merge_thirty_scans(0.003, 0.0, false, 5);
  EXPECT_EQ(fine.map.size(), fine_fixed.map.size());
}

TEST(LineMapFidelity, DistancesToTheNearestSegment)
{
  const std::vector<LineSegment> segs{{Vector2d(0, 0), Vector2d(2, 0), 0, 1}, {Vector2d(3, -1), Vector2d(3, 1), 0, 1}};
  const std::vector<Vector2d> pts{Vector2d(1, 0.01), Vector2d(2.9, 0.5), Vector2d(2.5, 0.0), Vector2d(1, 5)};
  const LineMapFidelity f = measure_fidelity(pts, segs, 0.05, 0.5);
  EXPECT_EQ(f.points, 4);
  EXPECT_EQ(f.explained, 1);   // only the first is within 5 cm (the second is 10 cm off)
  // 0.01 + 0.1 + 0.5 (beside the end of the first, 0.5 from both) + 0.5 (capped)
  EXPECT_NEAR(f.sum_distance, 1.11, 1e-9);
  EXPECT_NEAR(f.mean_distance(), 1.11 / 4, 1e-9);
  EXPECT_EQ(measure_fidelity(pts, {}, 0.05, 0.5).explained, 0);
}

TEST(LineMapFidelity, IndexAgreesWithBruteForce)
{
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-5, 5), len(0.05, 4);
  std::vector<LineSegment> segs;
  for (int i = 0; i < 60; ++i) {
    const Vector2d a(u(rng), u(rng));
    const double t = u(rng);
    segs.push_back({a, a + len(rng) * Vector2d(std::cos(t), std::sin(t)), 0, 1});
  }
  segs.push_back({Vector2d(1, -3), Vector2d(1, 3), 0, 1});   // vertical
  const double cap = 0.4;
  const SegmentIndex index(segs, cap);
  for (int k = 0; k < 2000; ++k) {
    const Vector2d p(u(rng), u(rng));
    double brute = cap;
    for (const auto& s : segs) brute = std::min(brute, point_segment_distance(p, s.a, s.b));
    ASSERT_NEAR(index.nearest_distance(p), brute, 1e-12) << p.transpose();
  }
}

}  // namespace
}  // namespace rgnav::rg_kernel
