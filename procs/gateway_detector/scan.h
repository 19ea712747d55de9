// A laser scan as the gateway detector sees it: plain numbers in the laser frame, where every
// beam is a ray from the origin. All detection geometry works in this frame (the measures of
// diss. 4.1.2 and 4.2.1 are defined along the sensor's rays); results are moved to the base
// frame with base_from_laser only at the end.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::gateway_detector {

using Vec2 = Eigen::Vector2d;

struct Scan
{
  int64_t utime = 0;
  int64_t scan_id = 0;
  double angle_min = -M_PI / 2;
  double angle_increment = M_PI / 180;
  double range_min = 0.0;
  double range_max = 8.183;
  std::vector<double> ranges;  // [m] 0 / < range_min: invalid; >= range_max: no return

  size_t size() const { return ranges.size(); }
  double bearing(size_t i) const { return angle_min + angle_increment * static_cast<double>(i); }
  Vec2 direction(size_t i) const { const double a = bearing(i); return {std::cos(a), std::sin(a)}; }
  bool hit(size_t i) const { return ranges[i] >= range_min && ranges[i] > 0.0 && ranges[i] < range_max; }
  bool no_return(size_t i) const { return ranges[i] >= range_max; }
  bool invalid(size_t i) const { return !hit(i) && !no_return(i); }
  Vec2 point(size_t i) const { return ranges[i] * direction(i); }
  // Index of the beam nearest to bearing a (clamped to the field of view).
  size_t index_of(double bearing) const;
};

// The scan plus where it was taken: map_from_base (odometry or SLAM frame) and the laser mount.
struct PosedScan
{
  Scan scan;
  geometry::Pose2 map_from_base;
  geometry::Pose2 base_from_laser;
  geometry::Pose2 map_from_laser() const { return map_from_base * base_from_laser; }
};

}  // namespace rgnav::gateway_detector
