// Node adapter: scans (LASER_FRONT + ODOMETRY, or ALIGNED_SCAN) and OBJECTS_3D in,
// GATEWAY_HYPOTHESES (every scan) and GATEWAY_EVENTS out.
#pragma once

#include <deque>
#include <map>
#include <string>

#include "config/config.h"
#include "gateway_detector/gateway_detector.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/objects3d_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "runtime/node.h"

namespace rgnav::gateway_detector {

struct NodeChannels
{
  std::string input = "laser";   // "laser" (LASER_FRONT + ODOMETRY) or "aligned" (ALIGNED_SCAN)
  std::string laser = "LASER_FRONT";
  std::string odometry = "ODOMETRY";
  std::string aligned_scan = "ALIGNED_SCAN";
  std::string objects = "OBJECTS_3D";
  std::string hypotheses = "GATEWAY_HYPOTHESES";
  std::string events = "GATEWAY_EVENTS";
};
NodeChannels load_node_channels(const config::Config& channels);

class GatewayDetectorNode
{
 public:
  // base_from_laser (the robot description's) for LASER_FRONT input; ALIGNED_SCAN carries its own.
  GatewayDetectorNode(runtime::Node& node, GatewayDetector detector, NodeChannels channels, geometry::Pose2 base_from_laser);

  int64_t scans_processed() const { return scans_; }

 private:
  void on_laser(const laser_scan_t& m);
  void on_odometry(const odometry_t& m);
  void on_aligned(const aligned_scan_t& m);
  void on_objects(const objects3d_t& m);
  void process(const PosedScan& s, const geometry::Pose2& odom_from_base);
  bool odometry_at(int64_t utime, geometry::Pose2* out) const;

  runtime::Node& node_;
  GatewayDetector detector_;
  const NodeChannels channels_;
  const geometry::Pose2 base_from_laser_;
  std::deque<std::pair<int64_t, geometry::Pose2>> odometry_;  // utime -> odom_from_base
  std::map<int64_t, geometry::Pose2> map_from_odom_;          // per scan id, recent scans
  int64_t last_scan_id_ = 0;
  int64_t scans_ = 0;
  bool warned_no_odometry_ = false;
};

}  // namespace rgnav::gateway_detector
