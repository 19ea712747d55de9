#include "localizer/motion_model.h"

#include <cmath>

namespace rgnav::localizer {

MotionStd motion_std(const geometry::Pose2& delta, const MotionNoise& n)
{
  const double d = delta.translation().norm();
  const double turn = std::fabs(delta.theta());
  MotionStd s;
  // Relative (systematic-like) and random-walk parts add as variances.
  s.along = std::sqrt(std::pow(n.translation_per_m * d, 2) + n.translation_per_sqrt_m * n.translation_per_sqrt_m * d);
  s.lateral = n.lateral_per_m * d;
  s.rotation = std::sqrt(std::pow(n.rotation_per_rad * turn, 2) + n.rotation_per_sqrt_rad * n.rotation_per_sqrt_rad * turn +
                         std::pow(n.rotation_per_m * d, 2) + n.rotation_per_sqrt_m * n.rotation_per_sqrt_m * d);
  return s;
}

geometry::Pose2 sample_motion(const geometry::Pose2& delta, const MotionNoise& noise, std::mt19937_64& rng)
{
  const MotionStd s = motion_std(delta, noise);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double d = delta.translation().norm();
  // Along / across the direction of travel (for a pure turn: the base's own axes).
  const Eigen::Vector2d along = d > 1e-9 ? Eigen::Vector2d(delta.translation() / d) : Eigen::Vector2d(1, 0);
  const Eigen::Vector2d across(-along.y(), along.x());
  const Eigen::Vector2d t = delta.translation() + s.along * n01(rng) * along + s.lateral * n01(rng) * across;
  return geometry::Pose2(t, delta.theta() + s.rotation * n01(rng));
}

}  // namespace rgnav::localizer
