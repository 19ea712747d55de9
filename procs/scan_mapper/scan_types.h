// The plain inputs of the scan mapper (no LCM): scans and odometry samples.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "scan_mapper/pose_math.h"

namespace rgnav::scan_mapper {

struct Scan
{
  int64_t utime = 0;    // [us] message time of the scan
  int64_t scan_id = 0;  // id of the LASER_FRONT message
  float angle_min = 0.f, angle_increment = 0.f, range_min = 0.f, range_max = 0.f;
  std::vector<float> ranges;  // [m]
};

struct OdometrySample
{
  int64_t utime = 0;
  Pose2 odom_from_base;
};

using Points = std::vector<Eigen::Vector2d>;

}  // namespace rgnav::scan_mapper
