#include "scan_mapper/odometry_scale.h"

#include <algorithm>
#include <cmath>

namespace rgnav::scan_mapper {

void OdometryScale::add(const Pose2& odometry_increment, const Pose2& measured_increment)
{
  if (!enabled()) return;
  const double d = translation_norm(odometry_increment);
  if (d < options_.min_step_m) return;
  const double along = (measured_increment.x() * odometry_increment.x() + measured_increment.y() * odometry_increment.y()) / d;
  const double keep = std::exp(-d / options_.window_m);
  sum_measured_odometry_ = keep * sum_measured_odometry_ + along * d;
  sum_odometry_squared_ = keep * sum_odometry_squared_ + d * d;
  travel_m_ += d;
}

double OdometryScale::scale() const
{
  if (!enabled() || travel_m_ < options_.min_travel_m || sum_odometry_squared_ <= 0.0) return 1.0;
  return std::clamp(sum_measured_odometry_ / sum_odometry_squared_, 1.0 - options_.max_error, 1.0 + options_.max_error);
}

Pose2 OdometryScale::corrected(const Pose2& odometry_increment) const
{
  const double s = scale();
  return Pose2{s * odometry_increment.x(), s * odometry_increment.y(), odometry_increment.theta()};
}

}  // namespace rgnav::scan_mapper
