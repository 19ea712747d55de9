#include "sim/sim_conversions.h"

#include "msg/conversions.h"

namespace rgnav::sim {

namespace {

// The simulator keeps theta in (-pi, pi] (apply_motion and the world loaders normalise it), so
// geometry::Pose2's normalisation leaves it as it is.
pose2d_t to_pose_msg(const Pose2& p) { return msg::to_msg(geometry::Pose2(p.x, p.y, p.theta)); }

// Odometry and truth share one message layout; only the pose and motion figures differ.
odometry_t odometry_msg(const OdometrySample& s, const Pose2& pose, double v, double omega, double distance)
{
  odometry_t m;
  m.utime = s.utime;
  m.seq = s.seq;
  m.odom_from_base = to_pose_msg(pose);
  m.v = v;
  m.omega = omega;
  m.distance = distance;
  m.status = odometry_t::STATUS_SIMULATED;
  return m;
}

}  // namespace

odometry_t to_odometry_msg(const OdometrySample& s)
{
  return odometry_msg(s, s.odom_from_base, s.v, s.omega, s.distance);
}

odometry_t to_truth_msg(const OdometrySample& s)
{
  return odometry_msg(s, s.world_from_base, s.true_v, s.true_omega, s.true_distance);
}

DriveCommand to_drive_command(const velocity_cmd_t& cmd) { return {cmd.v, cmd.omega}; }

}  // namespace rgnav::sim
