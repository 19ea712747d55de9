// The plain inputs of the scan mapper (no LCM): scans (sensors::LaserScan) and odometry samples.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "scan_mapper/pose_math.h"
#include "sensors/laser_scan.h"

namespace rgnav::scan_mapper {

struct OdometrySample
{
  int64_t utime = 0;
  Pose2 odom_from_base;
};

using Points = std::vector<Eigen::Vector2d>;

}  // namespace rgnav::scan_mapper
