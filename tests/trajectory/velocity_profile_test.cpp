#include "trajectory/velocity_profile.h"

#include <gtest/gtest.h>

#include <cmath>

#include "trajectory/construct.h"

namespace rgnav::trajectory {
namespace {

Chain mixed_chain()
{
  Chain c;
  c.push_back(Segment::line(Pose2(), 1.5));
  const Chain turn = smooth_turn(c.end(), M_PI / 2, 1.5);
  for (const auto& s : turn.segments()) c.append_at_end(s);
  c.append_at_end(Segment::line(Pose2(), 1.0));
  c.append_at_end(Segment::arc(Pose2(), -1.0, 0.8));  // curvature jump
  c.append_at_end(Segment::turn(Pose2(), 1.0));
  c.append_at_end(Segment::line(Pose2(), 0.6));
  return c;
}

TEST(VelocityProfile, RespectsEveryLimit)
{
  Limits lim;
  lim.v_max = 0.6;
  lim.a_max = 0.4;
  lim.a_lat_max = 0.3;
  lim.omega_max = 0.8;
  lim.alpha_max = 1.0;
  lim.omega_jump_max = 0.1;
  const Chain c = mixed_chain();
  const VelocityProfile p = VelocityProfile::compute(c, lim, 0.0, 0.0);
  ASSERT_TRUE(p.feasible());
  const double dt = 0.002;
  double prev_v = 0.0;
  for (double t = 0; t <= p.total_time(); t += dt) {
    const ProfileState st = p.at_time(t);
    EXPECT_LE(st.v, lim.v_max + 1e-9);
    if (st.turn < 0) {
      const double k = std::fabs(c.curvature_at(st.s));
      // Sampled limits: allow the small excess between 2 cm samples.
      EXPECT_LE(st.v * st.v * k, lim.a_lat_max * 1.05 + 1e-9) << st.s;
      EXPECT_LE(st.v * k, lim.omega_max * 1.05 + 1e-9) << st.s;
    } else {
      EXPECT_EQ(st.v, 0.0);
      EXPECT_LE(std::fabs(st.omega_turn), lim.omega_max + 1e-9);
    }
    EXPECT_LE(std::fabs(st.v - prev_v), lim.a_max * dt + 1e-6) << t;
    prev_v = st.v;
  }
  EXPECT_NEAR(p.at_time(p.total_time()).v, 0.0, 1e-9);
  EXPECT_NEAR(p.at_time(p.total_time()).s, c.length(), 1e-9);
  // At the curvature jump (line -> arc of curvature -1): v <= omega_jump_max / 1.
  const double s_jump = c.start_s(5);
  EXPECT_LE(p.speed_at(s_jump), 0.1 + 1e-9);
}

TEST(VelocityProfile, PredictedTimeEqualsIntegratedTime)
{
  Limits lim;
  const Chain c = mixed_chain();
  const VelocityProfile p = VelocityProfile::compute(c, lim, 0.0, 0.0);
  // Integrate ds / v(s) numerically along s (midpoint rule) plus the turn's own duration.
  double t = 0.0;
  const double ds = 1e-4;
  for (double s = ds / 2; s < c.length(); s += ds) t += ds / std::max(1e-6, p.speed_at(s));
  t += turn_duration(1.0, lim.omega_max, lim.alpha_max);
  EXPECT_NEAR(p.total_time(), t, 0.01 * t);
  // Straight line from rest: trapezoid with known closed form.
  Limits l2;
  l2.v_max = 0.5;
  l2.a_max = 0.5;
  const VelocityProfile q = VelocityProfile::compute(Chain({Segment::line(Pose2(), 3.0)}), l2, 0.0, 0.0);
  // accelerate 1 s over 0.25 m, cruise 2.5 m at 0.5 (5 s), brake 1 s: 7 s. The profile is
  // piecewise constant acceleration on 2 cm samples, so the corners are rounded slightly.
  EXPECT_NEAR(q.total_time(), 7.0, 1e-3);
  EXPECT_NEAR(q.time_at(1.5), 3.5, 1e-3);
  EXPECT_NEAR(q.time_at(1.5), q.total_time() / 2, 1e-9);  // symmetric
}

TEST(VelocityProfile, StartsAtCurrentSpeed)
{
  Limits lim;
  const VelocityProfile p = VelocityProfile::compute(Chain({Segment::line(Pose2(), 2.0)}), lim, 0.45, 0.0);
  EXPECT_NEAR(p.at_time(0).v, 0.45, 1e-12);
  EXPECT_TRUE(p.feasible());
  // Too fast for a sharp arc right away: flagged.
  const VelocityProfile q = VelocityProfile::compute(Chain({Segment::arc(Pose2(), 4.0, 1.0)}), lim, 0.6, 0.0);
  EXPECT_FALSE(q.feasible());
}

TEST(VelocityProfile, TurnInPlaceOnly)
{
  Limits lim;
  lim.omega_max = 1.0;
  lim.alpha_max = 2.0;
  const VelocityProfile p = VelocityProfile::compute(Chain({Segment::turn(Pose2(), -M_PI)}), lim, 0.0, 0.0);
  EXPECT_NEAR(p.total_time(), M_PI / 1.0 + 1.0 / 2.0, 1e-9);
  EXPECT_NEAR(p.at_time(p.total_time() - 1e-9).turn_angle, -M_PI, 1e-8);
  EXPECT_LT(p.at_time(p.total_time()).turn, 0);  // done: at rest
  EXPECT_NEAR(p.at_time(p.total_time() / 2).turn_angle, -M_PI / 2, 1e-9);
}

}  // namespace
}  // namespace rgnav::trajectory
