// Odometry of a synchro drive (all wheels steer together, so the robot's heading *is* the
// steering angle): integrates the translation encoder (path length s) and the rotation
// encoder (heading theta). Between two samples the wheels follow an arc of constant
// curvature (s and theta both change linearly in time under constant v and omega), which is
// integrated exactly:
//   x += ds / dtheta * (sin(theta1) - sin(theta0)),  y += ds / dtheta * (cos(theta0) - cos(theta1))
// (the straight-line limit for |dtheta| -> 0). Encoder counters wrap modulo 2^32.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>

namespace rgnav::can::base {

struct Pose2
{
  double x = 0.0;      // [m]
  double y = 0.0;      // [m]
  double theta = 0.0;  // [rad], normalised to (-pi, pi]
};

class SynchroOdometry
{
 public:
  // counts per m / per rad; sign -1 flips a drive's counting direction.
  SynchroOdometry(double translation_counts_per_m, int translation_sign, double rotation_counts_per_rad,
                  int rotation_sign);

  // New encoder readings. The first reading (and the first after rebaseline()) only sets the
  // reference.
  void update(int32_t translation_counts, int32_t rotation_counts);
  // The counters may have jumped (a drive rebooted): take the next reading as the reference.
  void rebaseline() { last_.reset(); }

  Pose2 pose() const;
  double distance() const { return distance_; }  // [m] total path length, monotonic

 private:
  double tcpm_, rcpr_;
  int tsign_, rsign_;
  std::optional<std::pair<int32_t, int32_t>> last_;
  double x_ = 0.0, y_ = 0.0, theta_ = 0.0;  // theta unwrapped
  double distance_ = 0.0;
};

// Counter difference modulo 2^32 (a wrap between two readings is a small step, not 2^32).
int64_t counter_delta(int32_t now, int32_t before);
double normalize_angle(double a);

}  // namespace rgnav::can::base
