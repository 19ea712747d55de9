// How well a line map describes the scans it was built from: the distance of every raw scan
// end point to the nearest map segment. Compression alone can be bought by throwing walls
// away or by smearing two walls into one line; this measure catches both, so the line map's
// compression (diss. 5.2, Fig. 5.4) is always reported next to it.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct LineMapFidelity
{
  int64_t points = 0;          // scan end points measured
  int64_t explained = 0;       // ... within the tolerance of some segment
  double sum_distance = 0;     // [m] sum of the distances, each capped at the cap
  double tolerance = 0.05;     // [m]
  double cap = 0.5;            // [m]

  double explained_share() const { return points > 0 ? static_cast<double>(explained) / static_cast<double>(points) : 0.0; }
  double mean_distance() const { return points > 0 ? sum_distance / static_cast<double>(points) : 0.0; }
  void add(const LineMapFidelity& other);   // sums counts (same tolerance and cap assumed)
};

// Distance from p to the segment a-b (to the nearer end point beyond its ends); a segment shorter
// than 1e-12 m counts as the point a.
double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Indexes segments on a grid so that the nearest one within `cap` is found without looking at
// every segment (region maps hold hundreds, a region's scans tens of thousands of points).
class SegmentIndex
{
 public:
  SegmentIndex(const std::vector<rgmap::LineSegment>& segments, double cap);
  // Distance to the nearest segment, or `cap` if none is nearer.
  double nearest_distance(const Eigen::Vector2d& p) const;
  // Index of the nearest segment closer than `cap`, or -1.
  int nearest(const Eigen::Vector2d& p, double* distance = nullptr) const;

 private:
  int64_t key(int64_t x, int64_t y) const;
  const std::vector<rgmap::LineSegment>& segments_;
  double cap_;
  double cell_;
  std::vector<std::pair<int64_t, int32_t>> cells_;   // (cell key, segment index), sorted by key
};

// Every point against the segments (points and segments in the same frame).
LineMapFidelity measure_fidelity(const std::vector<Eigen::Vector2d>& points, const std::vector<rgmap::LineSegment>& segments,
                                 double tolerance = 0.05, double cap = 0.5);

}  // namespace rgnav::rg_kernel
