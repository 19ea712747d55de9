// The gateway detector sees a laser scan (sensors::LaserScan) in the laser frame, where every
// beam is a ray from the origin. All detection geometry works in this frame (the measures of
// diss. 4.1.2 and 4.2.1 are defined along the sensor's rays); results are moved to the base
// frame with base_from_laser only at the end.
#pragma once

#include <Eigen/Core>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"

namespace rgnav::gateway_detector {

using Vec2 = Eigen::Vector2d;

// The scan plus where it was taken: map_from_base (odometry or SLAM frame) and the laser mount.
struct PosedScan
{
  sensors::LaserScan scan;
  geometry::Pose2 map_from_base;
  geometry::Pose2 base_from_laser;
  geometry::Pose2 map_from_laser() const { return map_from_base * base_from_laser; }
};

}  // namespace rgnav::gateway_detector
