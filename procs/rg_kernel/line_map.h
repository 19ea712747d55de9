// 2D line segment maps from laser scans (diss. 3.1.1, 5.2): every scan is cut into line
// segments (split-and-merge over the ordered scan points, total least squares fits), and the
// region's map merges them with the dissertation's restrictive laser parameters — segments
// whose angles differ by less than alpha_max, whose mean end-point distance to each other's
// line D_L is below D_L^max, and that overlap or leave a gap below D_gap^max become one
// segment spanning the two farthest end points. 30 scans of ~150 points compress to ~40
// segments (factor ~50, diss. Fig. 5.4).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct ExtractOptions
{
  double split_distance = 0.03;    // [m] a point farther than this from the fitted line splits it
  double max_point_gap = 0.25;     // [m] consecutive points farther apart belong to different segments
  int min_points = 5;              // fewer points make no segment
  double min_length = 0.15;        // [m]
};

struct MergeOptions
{
  double alpha_max = 3.0 * M_PI / 180.0;  // [rad]
  double dl_max = 0.020;                  // [m]
  double gap_max = 0.150;                 // [m]
};

// points: scan end points in scan order (beam order), in any common frame.
std::vector<rgmap::LineSegment> extract_segments(const std::vector<Eigen::Vector2d>& points, const ExtractOptions& o);

// Merges until no pair qualifies. Order-independent up to the ties of equal angles.
std::vector<rgmap::LineSegment> merge_segments(std::vector<rgmap::LineSegment> segments, const MergeOptions& o);

// Merges freshly extracted segments into an already merged map: each new segment is tried
// against the map, and a segment that grew by merging is tried again (merges cascade). Costs
// O(new x map) instead of O(map^2), so a region's map is updated per scan at constant cost.
std::vector<rgmap::LineSegment> merge_into(std::vector<rgmap::LineSegment> map, std::vector<rgmap::LineSegment> fresh,
                                           const MergeOptions& o);

// Mean distance of the four end points to the other segment's line (D_L of diss. Fig. 3.3).
double line_distance(const rgmap::LineSegment& a, const rgmap::LineSegment& b);

}  // namespace rgnav::rg_kernel
