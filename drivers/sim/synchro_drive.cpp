#include "sim/synchro_drive.h"

#include <algorithm>
#include <cmath>

namespace rgnav::sim {

namespace {

double slew(double current, double target, double max_change)
{
  return current + std::clamp(target - current, -max_change, max_change);
}

// Toward `target` over dt: braking (the magnitude falling, down to zero) at `brake`, speeding up
// (from zero, or further from it) at `accel`. A reversal brakes to zero first and spends the
// rest of the step speeding up the other way.
double slew_braking(double current, double target, double accel, double brake, double dt)
{
  const bool falls = current != 0.0 && (target * current < 0.0 || std::fabs(target) < std::fabs(current));
  if (!falls) return slew(current, target, accel * dt);
  if (target * current >= 0.0) return slew(current, target, brake * dt);  // slowing down
  const double brake_time = std::fabs(current) / brake;  // reversing: to zero first
  if (brake_time >= dt) return slew(current, target, brake * dt);
  return slew(0.0, target, accel * (dt - brake_time));
}

}  // namespace

BaseMotion SynchroDrive::step(const DriveCommand& target, double dt, bool ramped_by_drives)
{
  const double v_target = std::clamp(target.v, -options_.v_max, options_.v_max);
  const double w_target = std::clamp(target.omega, -options_.omega_max, options_.omega_max);
  const double v0 = v_, w0 = omega_;
  v_ = ramped_by_drives ? slew_braking(v_, v_target, options_.accel, options_.brake_decel, dt)
                       : slew(v_, v_target, options_.accel * dt);
  omega_ = slew(omega_, w_target, options_.alpha * dt);
  // Velocities ramp linearly within the step: the trapezoid gives the exact distances.
  return {0.5 * (v0 + v_) * dt, 0.5 * (w0 + omega_) * dt};
}

Pose2 apply_motion(const Pose2& pose, double ds, double dtheta)
{
  Pose2 out = pose;
  if (std::fabs(dtheta) < 1e-9) {
    // Straight line, heading at mid-step.
    out.x += ds * std::cos(pose.theta + 0.5 * dtheta);
    out.y += ds * std::sin(pose.theta + 0.5 * dtheta);
  } else {
    const double r = ds / dtheta;
    out.x += r * (std::sin(pose.theta + dtheta) - std::sin(pose.theta));
    out.y -= r * (std::cos(pose.theta + dtheta) - std::cos(pose.theta));
  }
  out.theta = normalize_angle(pose.theta + dtheta);
  return out;
}

}  // namespace rgnav::sim
