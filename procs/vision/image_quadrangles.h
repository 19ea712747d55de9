// Quadrangle hypotheses in an image (diss. 3.3.1): line segments (OpenCV's LSD line segment
// detector), merged where they lie on one line (3.1.1: alpha_max 1 degree — or, for a piece too
// short to hold its direction that well, atan(D_L / its length) —, D_L 2 px, D_gap 70 px),
// short ones dropped, then grouped in pairs of corners (3.1, Fig. 3.2, the non-restrictive case:
// alpha 20..160 degrees, DN_max 25 px, DO_min 15 px): two corners i-j and k-l form the quadrangle
// i-j-l-k when at least one of the links i-k, j-l is a corner too (the fourth corner may be hidden
// or faint), the angles there fit, and opposite sides lie apart. The quadrangle's corners are the
// intersections of its sides' lines; those with internal angles outside 26..154 degrees are not
// reconstructible from pixels (3.3.4.1) and are dropped, as are quadrangles inside others.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "vision/rectangle3d.h"

namespace rgnav::vision {

struct ImageSegment
{
  Eigen::Vector2d a, b;  // [px]
};

struct QuadrangleOptions
{
  double merge_angle_deg = 1.0;   // alpha_max of the merging
  double merge_distance_px = 2.0; // D_L^max
  double merge_gap_px = 70.0;     // D_gap^max
  double min_length_px = 20.0;    // L_min: shorter single segments are dropped
  double alpha_min_deg = 20.0;    // grouping: angle between neighbouring sides
  double alpha_max_deg = 160.0;
  double dn_max_px = 25.0;        // neighbouring sides at most this far apart
  double do_min_px = 15.0;        // opposite sides at least this far apart
  double min_internal_deg = 26.0; // reconstructible quadrangles (diss. 3.3.4.1)
  double max_internal_deg = 154.0;
  int max_segments = 300;         // the longest ones, at most (grouping is quadratic in them)
  int max_quadrangles = 200;
};

// Line segments of an 8-bit grey image (LSD).
std::vector<ImageSegment> detect_segments(const cv::Mat& gray);

// Segments on one line, overlapping or with a small gap, as one (diss. 3.1.1), then the short
// ones dropped and the longest max_segments kept.
std::vector<ImageSegment> merge_segments(std::vector<ImageSegment> segments, const QuadrangleOptions& options);

// Quadrangle hypotheses from merged segments (corners in order around), largest first.
std::vector<Quadrangle> group_quadrangles(const std::vector<ImageSegment>& segments, const QuadrangleOptions& options);

}  // namespace rgnav::vision
