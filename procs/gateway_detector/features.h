// Low-level features of diss. 4.1.1.1: the line segment scan L_LS (split-and-merge with
// orthogonal regression over each piece, after Gutmann), virtual lines (segments that lie on
// one line, represented by that line), and depth singularities (the near end of a range jump).
// All in the laser frame.
#pragma once

#include <vector>

#include "gateway_detector/scan.h"

namespace rgnav::gateway_detector {

// A line in Hesse normal form: points p with p . n(theta) = rho, rho >= 0.
struct Line
{
  double theta = 0.0;  // [rad] direction of the normal
  double rho = 0.0;    // [m] distance from the laser origin
  Vec2 normal() const { return {std::cos(theta), std::sin(theta)}; }
  Vec2 direction() const { return {-std::sin(theta), std::cos(theta)}; }
  double signed_distance(const Vec2& p) const { return p.dot(normal()) - rho; }
  Vec2 foot() const { return rho * normal(); }
};

// Orthogonal (total least squares) regression; rho made non-negative.
Line fit_line(const std::vector<Vec2>& points);
// Intersection of two lines; false if (nearly) parallel.
bool intersect(const Line& a, const Line& b, Vec2* out);
// Range along the ray at `bearing` from the origin to the line; negative or infinite if the
// ray never meets it.
double ray_range(const Line& line, double bearing);
// Smallest angle between two lines' directions, in [0, pi/2].
double angle_between(const Line& a, const Line& b);

struct Segment
{
  Line line;
  Vec2 a, b;           // end points projected on the line, in scan order
  size_t first = 0;    // beam indices covered
  size_t last = 0;
  int npoints = 0;
  double length() const { return (b - a).norm(); }
};

struct VirtualLine
{
  Line line;
  std::vector<int> segments;  // indices into the segment scan
  double support = 0.0;       // [m] summed length of its segments
  double t_min = 0.0, t_max = 0.0;  // extent along line.direction() from line.foot()
};

struct DepthSingularity
{
  size_t index = 0;   // beam whose range ends at the near side of the jump
  Vec2 point;         // P_ds
  int side = 0;       // +1: the far neighbour is at a larger bearing (CCW), -1: smaller
};

struct FeatureOptions
{
  double cluster_gap = 0.25;          // [m] plus range * beam angle: consecutive points further apart start a new cluster
  double split_distance = 0.04;       // [m] a piece is split at its farthest point from the chord beyond this
  int min_segment_points = 5;
  double min_segment_length = 0.25;   // [m]
  double virtual_line_angle = 0.10;   // [rad] segments on one virtual line differ in angle by less
  double virtual_line_distance = 0.12;  // [m] and their end points lie this close to the line
  double depth_jump = 0.5;            // [m] Delta d_min
};

struct ScanFeatures
{
  std::vector<Segment> segments;         // L_LS
  std::vector<VirtualLine> virtual_lines;
  std::vector<DepthSingularity> singularities;
};

std::vector<Segment> extract_segments(const sensors::LaserScan& scan, const FeatureOptions& options);
std::vector<VirtualLine> group_virtual_lines(const std::vector<Segment>& segments, const FeatureOptions& options);
std::vector<DepthSingularity> depth_singularities(const sensors::LaserScan& scan, double depth_jump);
ScanFeatures extract_features(const sensors::LaserScan& scan, const FeatureOptions& options);

}  // namespace rgnav::gateway_detector
