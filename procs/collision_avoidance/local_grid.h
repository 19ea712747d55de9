// The local map rasterised for searches on a grid (the detours of grid_path.h, the give-way
// search of give_way.h): each cell's distance to the nearest obstacle point (OpenCV's exact
// Euclidean distance transform, less half a cell diagonal: points sit anywhere in their cell),
// and what the kept scans saw of it: free (inside a scan's outline), in the shadow of an
// obstacle (inside a scan's field of view, behind what it hit), or nothing at all (outside
// every field of view: behind the robot).
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include <vector>

#include "collision_avoidance/local_map.h"

namespace rgnav::collision_avoidance {

class LocalGrid
{
 public:
  // Cells of `cell` over [lo, hi] (odom frame).
  LocalGrid(const LocalMap& map, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double cell);

  int width() const { return w_; }
  int height() const { return h_; }
  int index(int x, int y) const { return y * w_ + x; }
  // The cell holding p, clamped to the grid.
  Eigen::Vector2i cell_of(const Eigen::Vector2d& p) const;
  Eigen::Vector2d centre(int x, int y) const;
  // [m] to the nearest obstacle point, on the safe side.
  double clearance(int x, int y) const;
  bool seen(int x, int y) const { return seen_.at<uint8_t>(y, x) != 0; }
  // Seen, or in the shadow of something seen.
  bool in_view(int x, int y) const { return seen(x, y) || cone_.at<uint8_t>(y, x) != 0; }

 private:
  Eigen::Vector2d lo_;
  double cell_;
  int w_ = 0, h_ = 0;
  cv::Mat dist_;  // distance transform [cells]
  cv::Mat seen_, cone_;
};

// A path of points (odom frame, `from` first) reduced to the corners of a line-of-sight
// simplification whose every straight leg keeps `clearance` from the map's points (checked
// on the exact points, not the grid); where the start is closer than that, the first leg may
// not get closer than the start is. `from` itself is not among the corners.
std::vector<Eigen::Vector2d> line_of_sight_corners(const LocalMap& map, const std::vector<Eigen::Vector2d>& points,
                                                   double clearance);

}  // namespace rgnav::collision_avoidance
