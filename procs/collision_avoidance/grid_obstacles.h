// The obstacles collision avoidance takes from an OBSTACLES_3D grid (the vision's column
// projection): the centre of every cell at least `occupied_min` percent occupied, in the
// odometry frame. One function for the node and for benchmarks that feed the library directly.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::collision_avoidance {

// cells: row-major from min y, width x height, -1 unknown, 0 free ... 100 occupied.
inline std::vector<Eigen::Vector2d> grid_obstacle_points(const geometry::Pose2& odom_from_grid, double resolution, int width,
                                                         int height, const std::vector<int8_t>& cells, int occupied_min)
{
  std::vector<Eigen::Vector2d> pts;
  if (width <= 0 || height <= 0 || cells.size() < static_cast<size_t>(width) * static_cast<size_t>(height)) return pts;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (cells[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)] >= occupied_min)
        pts.push_back(odom_from_grid * Eigen::Vector2d((x + 0.5) * resolution, (y + 0.5) * resolution));
  return pts;
}

}  // namespace rgnav::collision_avoidance
