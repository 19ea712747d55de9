// The two points of a small set farthest apart (first such pair in index order): the footprint of
// an upright 3D rectangle seen from above spans its two corners farthest apart.
#pragma once

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace rgnav::geometry {

inline std::pair<Eigen::Vector2d, Eigen::Vector2d> farthest_pair(const std::vector<Eigen::Vector2d>& points)
{
  std::pair<Eigen::Vector2d, Eigen::Vector2d> best{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  double best_d2 = -1.0;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      if ((points[i] - points[j]).squaredNorm() > best_d2) {
        best_d2 = (points[i] - points[j]).squaredNorm();
        best = {points[i], points[j]};
      }
  return best;
}

}  // namespace rgnav::geometry
