#include "scan_mapper/scan_mapper_conversions.h"

namespace rgnav::scan_mapper {
namespace {
void copy_covariance(const Eigen::Matrix3d& c, double* out)
{
  for (int i = 0; i < 9; ++i) out[i] = c(i / 3, i % 3);
}
}  // namespace

Pose2 to_pose(const pose2d_t& m) { return {m.x, m.y, normalize_angle(m.theta)}; }

pose2d_t to_message(const Pose2& p)
{
  pose2d_t m;
  m.x = p.x();
  m.y = p.y();
  m.theta = normalize_angle(p.theta());
  return m;
}

Scan to_scan(const laser_scan_t& m)
{
  Scan s;
  s.utime = m.utime;
  s.scan_id = m.scan_id;
  s.angle_min = m.angle_min;
  s.angle_increment = m.angle_increment;
  s.range_min = m.range_min;
  s.range_max = m.range_max;
  s.ranges = m.ranges;
  return s;
}

laser_scan_t to_message(const Scan& s, const std::string& sensor)
{
  laser_scan_t m;
  m.utime = s.utime;
  m.scan_id = s.scan_id;
  m.sensor = sensor;
  m.angle_min = s.angle_min;
  m.angle_increment = s.angle_increment;
  m.range_min = s.range_min;
  m.range_max = s.range_max;
  m.scan_time = 0.f;
  m.nranges = static_cast<int32_t>(s.ranges.size());
  m.ranges = s.ranges;
  m.nintensities = 0;
  return m;
}

OdometrySample to_odometry(const odometry_t& m) { return {m.utime, to_pose(m.odom_from_base)}; }

aligned_scan_t to_aligned_scan(const ScanNode& node, const Pose2& base_from_laser, const std::string& sensor)
{
  aligned_scan_t m;
  m.utime = node.scan.utime;
  m.scan_id = node.scan.scan_id;
  m.revision = node.revision;
  m.odom_from_base = to_message(node.odom_from_base);
  m.map_from_base = to_message(node.map_from_base);
  copy_covariance(node.covariance, m.covariance);
  m.base_from_laser = to_message(base_from_laser);
  m.scan = to_message(node.scan, sensor);
  return m;
}

slam_pose_t to_slam_pose(const ScanNode& node, const Pose2& map_from_odom)
{
  slam_pose_t m;
  m.utime = node.scan.utime;
  m.scan_id = node.scan.scan_id;
  m.map_from_base = to_message(node.map_from_base);
  copy_covariance(node.covariance, m.covariance);
  m.map_from_odom = to_message(map_from_odom);
  return m;
}

}  // namespace rgnav::scan_mapper
