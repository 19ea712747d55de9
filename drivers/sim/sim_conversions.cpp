#include "sim/sim_conversions.h"

#include "msg/conversions.h"

namespace rgnav::sim {

namespace {

// The simulator keeps theta in (-pi, pi] (apply_motion and the world loaders normalise it), so
// geometry::Pose2's normalisation leaves it as it is.
pose2d_t to_pose_msg(const Pose2& p) { return msg::to_msg(geometry::Pose2(p.x, p.y, p.theta)); }

}  // namespace

odometry_t to_odometry_msg(const OdometrySample& s)
{
  odometry_t m;
  m.utime = s.utime;
  m.seq = s.seq;
  m.odom_from_base = to_pose_msg(s.odom_from_base);
  m.v = s.v;
  m.omega = s.omega;
  m.distance = s.distance;
  m.status = odometry_t::STATUS_SIMULATED;
  return m;
}

odometry_t to_truth_msg(const OdometrySample& s)
{
  odometry_t m;
  m.utime = s.utime;
  m.seq = s.seq;
  m.odom_from_base = to_pose_msg(s.world_from_base);
  m.v = s.true_v;
  m.omega = s.true_omega;
  m.distance = s.true_distance;
  m.status = odometry_t::STATUS_SIMULATED;
  return m;
}

DriveCommand to_drive_command(const velocity_cmd_t& cmd) { return {cmd.v, cmd.omega}; }

}  // namespace rgnav::sim
