#include <gtest/gtest.h>

#include "scan_mapper/relations_metric.h"

namespace sm = rgnav::scan_mapper;

TEST(RelationsMetric, SelectsConsecutiveAndLoopPairs)
{
  // Out along x and back: poses 0 and 4 are 0.5 m apart and 40 s apart; 1 and 3 too but only 20 s.
  const std::vector<sm::TimedPose> ref = {
      {0, {0, 0, 0}}, {10'000'000, {1, 0, 0}}, {20'000'000, {2, 0, 0}}, {30'000'000, {1, 0.5, M_PI}}, {40'000'000, {0, 0.5, M_PI}}};
  const auto rel = sm::select_relations(ref);
  const std::vector<std::pair<size_t, size_t>> expected = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {0, 4}};
  EXPECT_EQ(rel, expected);
}

TEST(RelationsMetric, HandComputedErrors)
{
  // Reference: three poses on a line. Estimate: the second step is 0.1 m too long and the
  // last pose is rotated by 2 deg.
  const std::vector<sm::Pose2> ref = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const double d2 = 2 * M_PI / 180;
  const std::vector<sm::Pose2> est = {{0, 0, 0}, {1, 0, 0}, {2.1, 0, d2}};
  const auto e = sm::relation_error(est, ref, {{0, 1}, {1, 2}});
  EXPECT_EQ(e.count, 2u);
  EXPECT_NEAR(e.trans_mean_m, 0.05, 1e-12);  // errors 0 and 0.1
  EXPECT_NEAR(e.trans_std_m, 0.05, 1e-12);
  EXPECT_NEAR(e.rot_mean_deg, 1.0, 1e-9);    // errors 0 and 2 deg
  EXPECT_NEAR(e.rot_std_deg, 1.0, 1e-9);
}

TEST(RelationsMetric, RelationErrorIgnoresAGlobalRigidOffset)
{
  const std::vector<sm::Pose2> ref = {{0, 0, 0}, {1, 0, 0.1}, {2, 1, 0.5}};
  std::vector<sm::Pose2> est;
  const sm::Pose2 offset{3, -2, 1.0};
  for (const auto& p : ref) est.push_back(offset * p);
  const auto e = sm::relation_error(est, ref, {{0, 1}, {1, 2}, {0, 2}});
  EXPECT_LT(e.trans_mean_m, 1e-12);
  EXPECT_LT(e.rot_mean_deg, 1e-9);
  EXPECT_LT(sm::ate_rmse(est, ref), 1e-9);
}

TEST(RelationsMetric, AteOfAShiftedPoint)
{
  // Two of four points agree after alignment except one displaced by 0.4 m.
  const std::vector<sm::Pose2> ref = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<sm::Pose2> est = ref;
  est[2] = sm::Pose2(est[2].x() + 0.4, est[2].y(), est[2].theta());
  const double ate = sm::ate_rmse(est, ref);
  EXPECT_GT(ate, 0.1);
  EXPECT_LT(ate, 0.2);  // alignment spreads the error: below 0.4 / sqrt(4) = 0.2
}
