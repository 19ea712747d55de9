#include "sim/protocol_conversions.h"

#include <cmath>

namespace rgnav::sim {

double counts_to_units(double counts, const can::base::AxisOptions& axis)
{
  return counts * axis.sign / axis.counts_per_unit;
}

double units_to_counts(double units, const can::base::AxisOptions& axis)
{
  return units * axis.counts_per_unit * axis.sign;
}

DriveCommand command_from_demands(double translation_counts_per_s, double rotation_counts_per_s, const DriveAxes& axes)
{
  return {counts_to_units(translation_counts_per_s, axes.translation),
          counts_to_units(rotation_counts_per_s, axes.rotation)};
}

EncoderReadings encoder_readings(const Simulator& sim, const DriveAxes& axes)
{
  const OdometryErrorOptions& e = sim.options().odometry;
  const double v = sim.drive().v();
  const double v_measured = v * (1.0 + e.scale_translation);
  const double omega_measured = sim.drive().omega() * (1.0 + e.scale_rotation) + e.bias_rotation_per_m * std::fabs(v);
  EncoderReadings r;
  r.translation.velocity = units_to_counts(v_measured, axes.translation);
  r.translation.position = units_to_counts(sim.odometry().translation_total(), axes.translation);
  r.rotation.velocity = units_to_counts(omega_measured, axes.rotation);
  r.rotation.position = units_to_counts(sim.odometry().rotation_total(), axes.rotation);
  return r;
}

}  // namespace rgnav::sim
