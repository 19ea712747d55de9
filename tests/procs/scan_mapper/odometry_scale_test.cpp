#include "scan_mapper/odometry_scale.h"

#include <gtest/gtest.h>

#include <random>

namespace sm = rgnav::scan_mapper;

namespace {

sm::OdometryScaleOptions options()
{
  sm::OdometryScaleOptions o;
  o.window_m = 50.0;
  o.min_step_m = 0.1;
  o.min_travel_m = 5.0;
  o.max_error = 0.1;
  return o;
}

}  // namespace

TEST(OdometryScale, LearnsHowLongTheOdometryIs)
{
  // Odometry 2 % long: 0.2 m steps that were 0.196 m, measured to 1 cm, in changing directions.
  sm::OdometryScale scale(options());
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int i = 0; i < 200; ++i) {
    const double heading = 0.05 * i;
    const sm::Pose2 odometry{0.2 * std::cos(heading), 0.2 * std::sin(heading), 0.01};
    const sm::Pose2 measured{odometry.x() / 1.02 + noise(rng), odometry.y() / 1.02 + noise(rng), 0.01};
    scale.add(odometry, measured);
    if (scale.measured_travel_m() < 5.0) {
      EXPECT_EQ(scale.scale(), 1.0) << "applied before min_travel_m";
    }
  }
  EXPECT_NEAR(scale.scale(), 1.0 / 1.02, 0.003);
  const sm::Pose2 c = scale.corrected({1.02, 0.0, 0.3});
  EXPECT_NEAR(c.x(), 1.0, 0.003);
  EXPECT_DOUBLE_EQ(c.theta(), 0.3);  // the heading is left alone
}

TEST(OdometryScale, LeavesOutTurnsOnTheSpotAndStaysWithinBounds)
{
  sm::OdometryScale scale(options());
  // Turns on the spot: translation too short to say anything (a 2 cm wobble "measured" as 0).
  for (int i = 0; i < 1000; ++i) scale.add({0.02, 0.0, 0.2}, {0.0, 0.0, 0.2});
  EXPECT_EQ(scale.measured_travel_m(), 0.0);
  EXPECT_EQ(scale.scale(), 1.0);
  // Matches that say half the odometry: held to 1 - max_error.
  for (int i = 0; i < 100; ++i) scale.add({0.2, 0.0, 0.0}, {0.1, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(scale.scale(), 0.9);
}

TEST(OdometryScale, ForgetsOverItsWindow)
{
  // 100 m at 2 % long, then the wheels change (a new tyre): 3 % short. Four windows on, the
  // old figure weighs exp(-4).
  sm::OdometryScale scale(options());
  for (int i = 0; i < 500; ++i) scale.add({0.2, 0.0, 0.0}, {0.2 / 1.02, 0.0, 0.0});
  EXPECT_NEAR(scale.scale(), 1.0 / 1.02, 1e-6);
  for (int i = 0; i < 1000; ++i) scale.add({0.2, 0.0, 0.0}, {0.2 / 0.97, 0.0, 0.0});
  EXPECT_NEAR(scale.scale(), 1.0 / 0.97, 0.005);
}

TEST(OdometryScale, WindowZeroIsOff)
{
  auto o = options();
  o.window_m = 0.0;
  sm::OdometryScale scale(o);
  for (int i = 0; i < 100; ++i) scale.add({0.2, 0.0, 0.0}, {0.1, 0.0, 0.0});
  EXPECT_FALSE(scale.enabled());
  EXPECT_EQ(scale.scale(), 1.0);
  EXPECT_DOUBLE_EQ(scale.corrected({0.2, 0.1, 0.0}).x(), 0.2);
}
