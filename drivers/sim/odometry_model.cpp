#include "sim/odometry_model.h"

#include <cmath>

namespace rgnav::sim {

void OdometryModel::integrate(const BaseMotion& truth)
{
  const double abs_ds = std::fabs(truth.ds);
  const double abs_dth = std::fabs(truth.dtheta);
  // A random walk: variance proportional to the increment.
  const double ds = truth.ds * (1.0 + options_.scale_translation) +
                    rng_.normal(options_.sigma_translation * std::sqrt(abs_ds));
  const double dtheta = truth.dtheta * (1.0 + options_.scale_rotation) +
                        options_.bias_rotation_per_m * abs_ds +
                        rng_.normal(std::sqrt(options_.sigma_rotation * options_.sigma_rotation * abs_dth +
                                              options_.sigma_rotation_per_m * options_.sigma_rotation_per_m * abs_ds));
  pose_ = apply_motion(pose_, ds, dtheta);
  distance_ += std::fabs(ds);
  translation_total_ += ds;
  rotation_total_ += dtheta;
}

}  // namespace rgnav::sim
