// LCM messages <-> the scan mapper's plain types. Poses and scans convert with common/msg.
#pragma once

#include "msg/conversions.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/pose2d_t.hpp"
#include "rgnav/slam_pose_t.hpp"
#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

OdometrySample to_odometry(const odometry_t& m);
aligned_scan_t to_aligned_scan(const ScanNode& node, const Pose2& base_from_laser, const std::string& sensor);
slam_pose_t to_slam_pose(const ScanNode& node, const Pose2& map_from_odom);

}  // namespace rgnav::scan_mapper
