// The B21r synchro drive: one motor turns all wheels (translation), one steers them all
// together (rotation), so v and omega are commanded and limited independently. The drive
// slews its velocities toward the targets within the acceleration limits; the base pose
// follows exact circular arcs over each step.
#pragma once

#include "sim/world.h"

namespace rgnav::sim {

struct SynchroDriveOptions
{
  double v_max = 0.9;        // [m/s]
  double omega_max = 2.0;    // [rad/s]
  double accel = 0.8;        // [m/s^2] translational acceleration (the motor's cruise ramp)
  // [m/s^2] translational deceleration of the body behind drives that ramp themselves
  // (protocol mode): while the speed's magnitude falls the body slows as hard as the drives
  // command, up to what the tyres' grip allows (a quick stop brakes far harder than the motor
  // accelerates). Rubber on a dry office floor grips with mu ~0.45-0.6: the low end, 0.46 g.
  // Above the CiA 402 drives' quick stop (4 m/s^2, 0x6085), so those set it.
  double brake_decel = 4.5;
  double alpha = 2.5;        // [rad/s^2] rotational acceleration limit
};

struct DriveCommand
{
  double v = 0.0;      // [m/s]
  double omega = 0.0;  // [rad/s]
};

// Motion of the base over one step, in the base frame at the start of the step.
struct BaseMotion
{
  double ds = 0.0;      // [m] signed arc length
  double dtheta = 0.0;  // [rad]
};

class SynchroDrive
{
 public:
  explicit SynchroDrive(const SynchroDriveOptions& options) : options_(options) {}

  // Advances the drive velocities toward `target` for dt seconds and returns the motion.
  // `ramped_by_drives`: the target is what drives with their own ramps already command (the
  // body then slows at up to brake_decel); otherwise it is a raw command, ramped at accel both
  // ways as the simulated drive's profile.
  BaseMotion step(const DriveCommand& target, double dt, bool ramped_by_drives = false);
  // The translation motor stops dead (a collision): rotation is unaffected.
  void stop_translation() { v_ = 0.0; }

  double v() const { return v_; }
  double omega() const { return omega_; }
  const SynchroDriveOptions& options() const { return options_; }

 private:
  const SynchroDriveOptions options_;
  double v_ = 0.0;
  double omega_ = 0.0;
};

// Pose after moving along an arc (ds, dtheta) from `pose` (exact for constant curvature).
Pose2 apply_motion(const Pose2& pose, double ds, double dtheta);

}  // namespace rgnav::sim
