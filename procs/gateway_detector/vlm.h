// Virtual line models (diss. 4.1.1.2): left and right parallels with the robot in between, a
// front line at right angles ahead, and a hidden line parallel to the front line, placed at a
// depth singularity close to the left or right line, or at one hallway width before the front
// line when no singularity explains it (clutter). Identical quadruples are removed.
#pragma once

#include <array>
#include <vector>

#include "gateway_detector/features.h"

namespace rgnav::gateway_detector {

struct Vlm
{
  Line left, right, front, hidden;
  // Gateway points around the quadrangle: 0 = left x hidden, 1 = left x front,
  // 2 = right x front, 3 = right x hidden. Sides: 0-1 left, 1-2 front, 2-3 right, 3-0 entry.
  std::array<Vec2, 4> points;
  Vec2 axis{1, 0};                 // unit hallway direction, pointing away from the robot
  bool hidden_from_singularity = false;

  Vec2 crossing_point() const { return 0.25 * (points[0] + points[1] + points[2] + points[3]); }
};

struct VlmOptions
{
  double hallway_width = 2.0;          // [m] d_hw, the expected hallway width
  double parallel_angle = 0.15;        // [rad] left and right lines differ by less
  double right_angle_tolerance = 0.3;  // [rad] front line at pi/2 +- this to the parallels
  double width_min_factor = 0.5;       // parallels between these multiples of d_hw apart
  double width_max_factor = 1.6;
  double min_side_support = 0.6;       // [m] of measured segments on a left/right line
  double min_front_support = 0.3;      // [m] on a front line
  double max_front_distance = 8.0;     // [m] front line intersections at most this far ahead
  double singularity_line_distance = 0.35;  // [m] a singularity this close to left/right explains a hidden line
  double min_depth_factor = 0.3;       // hidden line between these multiples of d_hw before the front line
  double max_depth_factor = 2.0;
  double duplicate_distance = 0.15;    // [m] VLMs whose gateway points all agree this well are one
  int max_hypotheses = 24;             // per scan, strongest support first (bounds the time per scan)
};

std::vector<Vlm> group_vlms(const ScanFeatures& features, const VlmOptions& options);

// Builds the VLM for given lines (false if lines do not intersect); used by grouping and tests.
bool make_vlm(const Line& left, const Line& right, const Line& front, const Line& hidden, Vlm* out);

}  // namespace rgnav::gateway_detector
