#include "base_driver/synchro_odometry.h"

#include <cmath>

namespace rgnav::can::base {

int64_t counter_delta(int32_t now, int32_t before)
{
  return static_cast<int32_t>(static_cast<uint32_t>(now) - static_cast<uint32_t>(before));
}

double normalize_angle(double a)
{
  a = std::remainder(a, 2.0 * M_PI);  // [-pi, pi]
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

SynchroOdometry::SynchroOdometry(double translation_counts_per_m, int translation_sign, double rotation_counts_per_rad,
                                 int rotation_sign)
    : tcpm_(translation_counts_per_m), rcpr_(rotation_counts_per_rad), tsign_(translation_sign), rsign_(rotation_sign)
{
}

void SynchroOdometry::update(int32_t translation_counts, int32_t rotation_counts)
{
  if (!last_) {
    last_ = std::make_pair(translation_counts, rotation_counts);
    return;
  }
  const double ds = static_cast<double>(counter_delta(translation_counts, last_->first)) * tsign_ / tcpm_;
  const double dth = static_cast<double>(counter_delta(rotation_counts, last_->second)) * rsign_ / rcpr_;
  last_ = std::make_pair(translation_counts, rotation_counts);
  const double th0 = theta_, th1 = theta_ + dth;
  if (std::fabs(dth) < 1e-9) {
    x_ += ds * std::cos(th0 + 0.5 * dth);
    y_ += ds * std::sin(th0 + 0.5 * dth);
  } else {
    const double r = ds / dth;
    x_ += r * (std::sin(th1) - std::sin(th0));
    y_ += r * (std::cos(th0) - std::cos(th1));
  }
  theta_ = th1;
  distance_ += std::fabs(ds);
}

Pose2 SynchroOdometry::pose() const { return {x_, y_, normalize_angle(theta_)}; }

}  // namespace rgnav::can::base
