// A static set of 2D points with surface normals and a uniform-grid index for nearest
// neighbour queries: the model side of point-to-line ICP.
#pragma once

#include <vector>

#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

class PointMap
{
 public:
  // normal_radius: neighbours within it define a point's normal (PCA); cell_size: index grid.
  PointMap(Points points, double normal_radius = 0.15, double cell_size = 0.25);
  // With normals computed before (e.g. per scan, then moved into the map frame): no PCA.
  PointMap(Points points, Points normals, std::vector<char> has_normal, double cell_size = 0.25);

  // Index of the nearest point within max_dist, or -1.
  int nearest(const Eigen::Vector2d& q, double max_dist) const;
  // ... among the points that may be the same surface as a point with oriented normal n:
  // points with a normal must face the same way (n . normal >= min_cos). With normals oriented
  // toward the sensor, this keeps the two faces of a thin wall apart (seen from a room and from
  // the corridor they are 10-20 cm apart, close enough for a nearest-neighbour mix-up).
  int nearest(const Eigen::Vector2d& q, double max_dist, const Eigen::Vector2d& n, double min_cos) const;

  const Points& points() const { return points_; }
  const Points& normals() const { return normals_; }
  const std::vector<char>& has_normals() const { return has_normal_; }
  const Eigen::Vector2d& normal(int i) const { return normals_[static_cast<size_t>(i)]; }
  // False where the neighbourhood is not line-like (corners, clutter, isolated points).
  bool has_normal(int i) const { return has_normal_[static_cast<size_t>(i)] != 0; }
  size_t size() const { return points_.size(); }

 private:
  void build_index();
  template <class F>
  void for_each_within(const Eigen::Vector2d& q, double r, F&& f) const;

  Points points_;
  Points normals_;
  std::vector<char> has_normal_;
  double cell_ = 0.25;
  double x0_ = 0.0, y0_ = 0.0;
  int w_ = 0, h_ = 0;
  std::vector<int> cell_start_;  // CSR: points of cell c are order_[cell_start_[c] .. cell_start_[c+1])
  std::vector<int> order_;
};

// Flips each normal to point from its point toward `viewpoint` (the sensor that saw it, same
// frame), so that a surface's normal says from which side it was seen.
void orient_normals_toward(const Points& points, const Eigen::Vector2d& viewpoint, Points* normals,
                           const std::vector<char>& has_normal);

}  // namespace rgnav::scan_mapper
