#include "sim/sim_conversions.h"

namespace rgnav::sim {

namespace {

pose2d_t to_pose_msg(const Pose2& p)
{
  pose2d_t m;
  m.x = p.x;
  m.y = p.y;
  m.theta = p.theta;
  return m;
}

}  // namespace

laser_scan_t to_laser_scan_msg(const LaserScan& scan)
{
  laser_scan_t m;
  m.utime = scan.utime;
  m.scan_id = scan.scan_id;
  m.sensor = scan.sensor;
  m.angle_min = static_cast<float>(scan.angle_min);
  m.angle_increment = static_cast<float>(scan.angle_increment);
  m.range_min = static_cast<float>(scan.range_min);
  m.range_max = static_cast<float>(scan.range_max);
  m.scan_time = static_cast<float>(scan.scan_time);
  m.nranges = static_cast<int32_t>(scan.ranges.size());
  m.ranges = scan.ranges;
  m.nintensities = 0;
  return m;
}

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
