// A region's line map as a distance field (Probabilistic Robotics 6.4): every cell holds the
// distance to the nearest line segment, from OpenCV's exact Euclidean distance transform of the
// rendered lines. Scan end points are scored by a lookup, so a particle costs one lookup per
// beam however many lines the region has.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cmath>

#include <optional>
#include <utility>
#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::localizer {

class LikelihoodField
{
 public:
  LikelihoodField() = default;
  // Covers the segments' bounding box grown by `margin`, clipped to `clip` (lo, hi) when given;
  // distances saturate at max_distance.
  LikelihoodField(const std::vector<rgmap::LineSegment>& segments, double resolution, double max_distance, double margin,
                  const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& clip = std::nullopt);

  // [m] distance from a region-frame point to the nearest line, interpolated bilinearly between
  // the four cell centres around it (a nearest-cell lookup would quantise every beam to the
  // cell, a bias of up to half a cell); max_distance off the field.
  float distance(const Eigen::Vector2d& p) const
  {
    const double fx = (p.x() - origin_.x()) * inv_resolution_ - 0.5;
    const double fy = (p.y() - origin_.y()) * inv_resolution_ - 0.5;
    const int cx = static_cast<int>(std::floor(fx));
    const int cy = static_cast<int>(std::floor(fy));
    if (cx < 0 || cy < 0 || cx + 1 >= distance_.cols || cy + 1 >= distance_.rows) return max_distance_;
    const float ax = static_cast<float>(fx - cx), ay = static_cast<float>(fy - cy);
    const float* r0 = distance_.ptr<float>(cy) + cx;
    const float* r1 = distance_.ptr<float>(cy + 1) + cx;
    return (1 - ay) * ((1 - ax) * r0[0] + ax * r0[1]) + ay * ((1 - ax) * r1[0] + ax * r1[1]);
  }
  double max_distance() const { return max_distance_; }
  bool empty() const { return distance_.empty(); }
  size_t bytes() const { return distance_.total() * sizeof(float); }

 private:
  // Replaces the cell values within two cells of segment s by the exact distance to it.
  void exact_near(const rgmap::LineSegment& s, double resolution);

  cv::Mat distance_;                   // CV_32F [m], row = y
  Eigen::Vector2d origin_{0, 0};       // region-frame position of cell (0,0)'s corner
  double inv_resolution_ = 1.0;
  float max_distance_ = 1.0f;
};

}  // namespace rgnav::localizer
