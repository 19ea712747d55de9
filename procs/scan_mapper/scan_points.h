// A scan → points in the robot (base) frame, thinned to a minimum spacing so that dense near
// ranges do not dominate the registration (Holz et al.'s sparse point maps, epsilon_D).
#pragma once

#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

struct PointFilterOptions
{
  double min_range_m = 0.1;   // closer readings are the robot itself or noise
  double max_range_m = 30.0;  // farther readings are too sparse and noisy to match
  double min_spacing_m = 0.05;  // consecutive kept points are at least this far apart
};

Points scan_to_points(const sensors::LaserScan& scan, const Pose2& base_from_laser, const PointFilterOptions& options);

// Keeps a point when it is at least `spacing` away from the previously kept one (scan order).
Points thin_points(const Points& points, double spacing);

Points transform_points(const Pose2& a_from_b, const Points& points_in_b);

}  // namespace rgnav::scan_mapper
