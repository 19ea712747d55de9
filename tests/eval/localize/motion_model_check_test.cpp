// The localizer's odometry noise (config/localizer.yaml motion_noise) checked against the
// simulator's odometry error model (config/sim.yaml odometry): over the increments the filter
// sees (0.1 m of driving, 5 deg of turning, as its update gate), the model's spread must cover
// the simulated odometry's error (systematic part included: the filter cannot know it) without
// being so wide that the cloud never converges.
#include <gtest/gtest.h>

#include <cmath>

#include "config/config.h"
#include "config/robot_description.h"
#include "localizer/localizer_options.h"
#include "localizer/motion_model.h"
#include "sim/odometry_model.h"
#include "sim/sim_options.h"

namespace rgnav::localize_eval {
namespace {

struct Spread
{
  double rms_along = 0, rms_rotation = 0;   // of the simulated odometry's error
};

// Error of the odometry increment against the true one, many times over.
Spread simulated_error(const sim::OdometryErrorOptions& o, double ds, double dtheta)
{
  sim::OdometryModel odom(o, sim::Rng(11));
  constexpr int kTrials = 4000, kSubsteps = 20;   // the simulator integrates in small steps
  double se_along = 0, se_rot = 0;
  geometry::Pose2 before(0, 0, 0);
  for (int k = 0; k < kTrials; ++k) {
    const auto p0 = odom.pose();
    for (int s = 0; s < kSubsteps; ++s) odom.integrate({ds / kSubsteps, dtheta / kSubsteps});
    const auto p1 = odom.pose();
    const geometry::Pose2 a(p0.x, p0.y, p0.theta), b(p1.x, p1.y, p1.theta);
    const geometry::Pose2 delta = a.between(b);
    se_along += std::pow(delta.translation().norm() * (ds < 0 ? -1 : 1) - ds, 2);
    se_rot += std::pow(geometry::normalize_angle(delta.theta() - dtheta), 2);
  }
  return {std::sqrt(se_along / kTrials), std::sqrt(se_rot / kTrials)};
}

class MotionModelCheck : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    const std::string dir = RGNAV_CONFIG_DIR;
    const auto robot = config::load_robot_description_file(dir + "/robot.yaml");
    const auto sim_cfg = config::Config::load(dir + "/sim.yaml");
    sim_ = sim::load_simulator_options(sim_cfg, robot).odometry;
    noise_ = localizer::load_localizer_options(config::Config::load(dir + "/localizer.yaml"), robot).localizer.motion;
  }
  sim::OdometryErrorOptions sim_;
  localizer::MotionNoise noise_;
};

TEST_F(MotionModelCheck, DrivingStraightIsCoveredButNotLost)
{
  const double ds = 0.1;
  const Spread e = simulated_error(sim_, ds, 0.0);
  const auto s = localizer::motion_std(geometry::Pose2(ds, 0, 0), noise_);
  EXPECT_GE(s.along, e.rms_along) << "distance noise narrower than the odometry's error";
  EXPECT_LE(s.along, 6 * e.rms_along + 0.01) << "distance noise far wider than the odometry's error";
  EXPECT_GE(s.rotation, e.rms_rotation) << "heading noise while driving narrower than the odometry's error";
  EXPECT_LE(s.rotation, 6 * e.rms_rotation + 0.01);
}

TEST_F(MotionModelCheck, TurningIsCoveredButNotLost)
{
  const double dth = 5 * M_PI / 180;
  const Spread e = simulated_error(sim_, 0.0, dth);
  const auto s = localizer::motion_std(geometry::Pose2(0, 0, dth), noise_);
  EXPECT_GE(s.rotation, e.rms_rotation) << "turn noise narrower than the odometry's error";
  EXPECT_LE(s.rotation, 6 * e.rms_rotation + 0.01);
}

}  // namespace
}  // namespace rgnav::localize_eval
