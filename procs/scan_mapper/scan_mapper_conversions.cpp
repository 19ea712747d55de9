#include "scan_mapper/scan_mapper_conversions.h"

namespace rgnav::scan_mapper {
namespace {
void copy_covariance(const Eigen::Matrix3d& c, double* out)
{
  for (int i = 0; i < 9; ++i) out[i] = c(i / 3, i % 3);
}
}  // namespace

OdometrySample to_odometry(const odometry_t& m) { return {m.utime, msg::to_pose2(m.odom_from_base)}; }

aligned_scan_t to_aligned_scan(const ScanNode& node, const Pose2& base_from_laser, const std::string& sensor)
{
  aligned_scan_t m;
  m.utime = node.scan.utime;
  m.scan_id = node.scan.scan_id;
  m.revision = node.revision;
  m.odom_from_base = msg::to_msg(node.odom_from_base);
  m.map_from_base = msg::to_msg(node.map_from_base);
  copy_covariance(node.covariance, m.covariance);
  m.base_from_laser = msg::to_msg(base_from_laser);
  m.scan = msg::to_msg(node.scan);
  // The configured sensor name and scan_time 0: the mapper's checkpoint (state_codec) keeps
  // neither, so a restored mapper publishes what a live one does.
  m.scan.sensor = sensor;
  m.scan.scan_time = 0.f;
  return m;
}

slam_pose_t to_slam_pose(const ScanNode& node, const Pose2& map_from_odom)
{
  slam_pose_t m;
  m.utime = node.scan.utime;
  m.scan_id = node.scan.scan_id;
  m.map_from_base = msg::to_msg(node.map_from_base);
  copy_covariance(node.covariance, m.covariance);
  m.map_from_odom = msg::to_msg(map_from_odom);
  return m;
}

}  // namespace rgnav::scan_mapper
