// Aligning a scan to the region's line map before its segments are merged (diss. 5.2: "scans
// are matched ... after each new scan has been successfully matched, the 2D line segment map is
// updated"). Scan poses carry errors of a few cm and a fraction of a degree (the scan mapper's
// estimates, or the published corrections of recorded logs); at D_L^max = 20 mm such an error
// turns one wall into two parallel segments. A small rigid correction by point-to-line least
// squares against the map lets the merge tests judge the geometry instead of the pose error.
// The correction is used for the line map only: the scan's pose stays as given everywhere else.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct LineAlignOptions
{
  bool enabled = true;
  double max_distance = 0.10;                    // [m] a point pairs with the nearest segment closer than this
  int iterations = 10;
  int min_matches = 30;                          // fewer paired points: no correction
  double max_translation = 0.03;                 // [m] (at the points' centroid) larger corrections are not
                                                 // trusted: none is applied
  double max_rotation = 0.5 * M_PI / 180.0;      // [rad]
};

// The rigid transform to apply to `points` (region frame) so that they lie best on `map`, or
// nullopt if too few points pair with segments or the correction exceeds the limits.
std::optional<geometry::Pose2> align_to_line_map(const std::vector<Eigen::Vector2d>& points,
                                                 const std::vector<rgmap::LineSegment>& map, const LineAlignOptions& o);

}  // namespace rgnav::rg_kernel
