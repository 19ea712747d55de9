// Exact odometry of the synchro drive against analytic arcs, and encoder wrap-around.
#include <gtest/gtest.h>

#include <cmath>

#include "base_driver/synchro_odometry.h"

namespace rgnav::can::base {
namespace {

constexpr double kCpm = 146000.0;  // counts per m
constexpr double kCpr = 19100.0;   // counts per rad

int32_t counts(double units, double per_unit, double offset = 0.0)
{
  const auto wide = static_cast<int64_t>(std::llround(units * per_unit + offset));
  return static_cast<int32_t>(static_cast<uint32_t>(wide));
}

TEST(SynchroOdometry, ArcOfConstantCurvatureIsExact)
{
  // v = 0.4 m/s, omega = 0.5 rad/s for 6 s, sampled at 100 Hz: a circle of radius 0.8 m.
  const double v = 0.4, w = 0.5, T = 6.0, R = v / w;
  SynchroOdometry odo(kCpm, 1, kCpr, 1);
  for (int k = 0; k <= 600; ++k) {
    const double t = T * k / 600.0;
    odo.update(counts(v * t, kCpm), counts(w * t, kCpr));
  }
  const Pose2 p = odo.pose();
  EXPECT_NEAR(p.x, R * std::sin(w * T), 2e-5);
  EXPECT_NEAR(p.y, R * (1.0 - std::cos(w * T)), 2e-5);
  EXPECT_NEAR(p.theta, std::remainder(w * T, 2 * M_PI), 1e-4);
  EXPECT_NEAR(odo.distance(), v * T, 1e-5);
}

TEST(SynchroOdometry, CoarseSamplesStayExactOnAnArc)
{
  // Exact integration does not need fine sampling: 4 samples over 3/4 of a circle.
  const double R = 1.5, turn = 1.5 * M_PI;
  SynchroOdometry odo(kCpm, 1, kCpr, 1);
  for (int k = 0; k <= 4; ++k) {
    const double th = turn * k / 4.0;
    odo.update(counts(R * th, kCpm), counts(th, kCpr));
  }
  EXPECT_NEAR(odo.pose().x, R * std::sin(turn), 1e-4);
  EXPECT_NEAR(odo.pose().y, R * (1 - std::cos(turn)), 1e-4);
}

TEST(SynchroOdometry, StraightLineTurnInPlaceAndReverse)
{
  SynchroOdometry odo(kCpm, 1, kCpr, 1);
  odo.update(0, 0);
  odo.update(0, counts(M_PI / 2, kCpr));  // turn in place
  EXPECT_NEAR(odo.pose().theta, M_PI / 2, 1e-4);
  EXPECT_NEAR(odo.pose().x, 0.0, 1e-9);
  odo.update(counts(-2.0, kCpm), counts(M_PI / 2, kCpr));  // 2 m backwards along +y heading
  EXPECT_NEAR(odo.pose().x, 0.0, 1e-4);
  EXPECT_NEAR(odo.pose().y, -2.0, 1e-5);
  EXPECT_NEAR(odo.distance(), 2.0, 1e-5);
}

TEST(SynchroOdometry, EncoderWrapAroundAndInvertedDrives)
{
  SynchroOdometry odo(kCpm, -1, kCpr, -1);
  const double near_wrap = 2147483647.0 - 1000.0;  // the counters are about to wrap
  for (int k = 0; k <= 100; ++k) {
    const double s = 0.01 * k;  // 1 m straight ahead, counted negatively
    odo.update(counts(-s, kCpm, -near_wrap), counts(0.0, kCpr, near_wrap));
  }
  EXPECT_NEAR(odo.pose().x, 1.0, 1e-5);
  EXPECT_NEAR(odo.pose().y, 0.0, 1e-9);
  EXPECT_EQ(counter_delta(INT32_MIN, INT32_MAX), 1);
  EXPECT_EQ(counter_delta(INT32_MAX, INT32_MIN), -1);
}

TEST(SynchroOdometry, RebaselineIgnoresCounterJumps)
{
  SynchroOdometry odo(kCpm, 1, kCpr, 1);
  odo.update(0, 0);
  odo.update(counts(1.0, kCpm), 0);
  odo.rebaseline();
  odo.update(123456789, -5555);  // the drive rebooted with another count
  odo.update(123456789 + counts(1.0, kCpm), -5555);
  EXPECT_NEAR(odo.pose().x, 2.0, 1e-5);
  EXPECT_NEAR(normalize_angle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(normalize_angle(-M_PI), M_PI, 1e-12);
}

}  // namespace
}  // namespace rgnav::can::base
