// Wheel odometry with the errors a real synchro drive shows: systematic (a wrong wheel
// radius scales distances, a misaligned steering gear scales turns and makes the robot
// "turn" while driving straight) and random (slip, encoder quantisation), the latter as
// random walks whose variance grows with the distance / angle travelled, so the error
// statistics do not depend on the simulator's step size.
#pragma once

#include "sim/rng.h"
#include "sim/synchro_drive.h"
#include "sim/world.h"

namespace rgnav::sim {

struct OdometryErrorOptions
{
  double scale_translation = 0.0;   // measured ds = (1 + this) * true ds
  double scale_rotation = 0.0;      // measured dtheta = (1 + this) * true dtheta
  double bias_rotation_per_m = 0.0; // [rad/m] heading drift while translating
  double sigma_translation = 0.0;   // [m / sqrt(m)] std of the distance error after 1 m
  double sigma_rotation = 0.0;      // [rad / sqrt(rad)] std of the heading error after 1 rad of turning
  double sigma_rotation_per_m = 0.0;// [rad / sqrt(m)] std of the heading error after 1 m of driving
};

class OdometryModel
{
 public:
  OdometryModel(const OdometryErrorOptions& options, Rng rng) : options_(options), rng_(rng) {}

  // Integrates one true base motion into the odometry estimate.
  void integrate(const BaseMotion& truth);

  const Pose2& pose() const { return pose_; }          // odom_from_base (odom frame = start pose)
  double distance() const { return distance_; }        // measured path length, monotonic
  // Cumulative measured signed translation and rotation (what encoders would count).
  double translation_total() const { return translation_total_; }
  double rotation_total() const { return rotation_total_; }

 private:
  const OdometryErrorOptions options_;
  Rng rng_;
  Pose2 pose_;
  double distance_ = 0.0;
  double translation_total_ = 0.0;
  double rotation_total_ = 0.0;
};

}  // namespace rgnav::sim
