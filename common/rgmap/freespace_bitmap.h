// The freespace map of a region (diss. 5.2): a binary grid, one bit per cell (1 = free),
// rotated and placed in the region frame. A 30 m^2 region at 15 cm needs ~200 bytes, where
// a float occupancy grid would need over 5 kB. Used for region features (area, moments, main
// axes), for checking that a pose lies in the region, and for placing particles.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::rgmap {

struct FreespaceFeatures
{
  double area = 0;                          // [m^2]
  Eigen::Vector2d centroid{0, 0};           // [m] region frame (first-order moments / area)
  Eigen::Matrix2d second_moments = Eigen::Matrix2d::Zero();  // [m^2] central, per unit area
  Eigen::Vector2d main_axes{0, 0};          // [m] 2 sigma extents along the principal axes, major first
};

class FreespaceBitmap
{
 public:
  FreespaceBitmap() = default;
  // An all-occupied grid of width x height cells of edge `resolution`, whose cell (0,0) corner
  // is at region_from_grid.
  FreespaceBitmap(double resolution, geometry::Pose2 region_from_grid, int width, int height);
  // From serialised bytes; throws std::invalid_argument if sizes disagree.
  FreespaceBitmap(double resolution, geometry::Pose2 region_from_grid, int width, int height,
                  std::vector<uint8_t> bytes);

  double resolution() const { return resolution_; }
  const geometry::Pose2& region_from_grid() const { return region_from_grid_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

  bool in_bounds(int cx, int cy) const { return cx >= 0 && cy >= 0 && cx < width_ && cy < height_; }
  bool free(int cx, int cy) const;
  void set_free(int cx, int cy, bool is_free);
  // Point in the region frame -> cell; false outside the grid.
  bool cell_of(const Eigen::Vector2d& region_point, int* cx, int* cy) const;
  bool is_free(const Eigen::Vector2d& region_point) const;
  // Marks free every cell the segment a->b crosses, excluding the cell holding b when
  // `exclude_end` (a laser beam: free up to its end point, which is an obstacle).
  void carve_ray(const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool exclude_end);
  int free_cells() const;
  FreespaceFeatures features() const;

 private:
  double resolution_ = 0.15;
  geometry::Pose2 region_from_grid_;
  int width_ = 0;
  int height_ = 0;
  std::vector<uint8_t> bytes_;   // row-major, LSB first
};

}  // namespace rgnav::rgmap
