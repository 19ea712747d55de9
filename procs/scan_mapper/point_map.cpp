#include "scan_mapper/point_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/symmetric_eigen2.h"

namespace rgnav::scan_mapper {

PointMap::PointMap(Points points, Points normals, std::vector<char> has_normal, double cell_size)
    : points_(std::move(points)), normals_(std::move(normals)), has_normal_(std::move(has_normal)), cell_(cell_size)
{
  normals_.resize(points_.size(), Eigen::Vector2d::Zero());
  has_normal_.resize(points_.size(), 0);
  build_index();
}

PointMap::PointMap(Points points, double normal_radius, double cell_size)
    : points_(std::move(points)), cell_(cell_size)
{
  build_index();
  normals_.assign(points_.size(), Eigen::Vector2d::Zero());
  has_normal_.assign(points_.size(), 0);
  for (size_t i = 0; i < points_.size(); ++i) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    int n = 0;
    for_each_within(points_[i], normal_radius, [&](int j) {
      mean += points_[static_cast<size_t>(j)];
      ++n;
    });
    if (n < 3) continue;
    mean /= n;
    for_each_within(points_[i], normal_radius, [&](int j) {
      const Eigen::Vector2d d = points_[static_cast<size_t>(j)] - mean;
      cov += d * d.transpose();
    });
    const geometry::SymmetricEigen2 es = geometry::symmetric_eigen(cov);
    const double l0 = es.values(0), l1 = es.values(1);
    if (l1 <= 0.0 || l0 > 0.1 * l1) continue;  // not a line
    normals_[i] = es.vectors.col(0);
    has_normal_[i] = 1;
  }
}

void PointMap::build_index()
{
  if (points_.empty()) return;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
  x0_ = y0_ = std::numeric_limits<double>::infinity();
  for (const auto& p : points_) {
    x0_ = std::min(x0_, p.x());
    y0_ = std::min(y0_, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
  w_ = static_cast<int>((x1 - x0_) / cell_) + 1;
  h_ = static_cast<int>((y1 - y0_) / cell_) + 1;
  std::vector<int> cell_of(points_.size());
  cell_start_.assign(static_cast<size_t>(w_) * h_ + 1, 0);
  for (size_t i = 0; i < points_.size(); ++i) {
    const int cx = static_cast<int>((points_[i].x() - x0_) / cell_);
    const int cy = static_cast<int>((points_[i].y() - y0_) / cell_);
    cell_of[i] = cy * w_ + cx;
    ++cell_start_[static_cast<size_t>(cell_of[i]) + 1];
  }
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  order_.resize(points_.size());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (size_t i = 0; i < points_.size(); ++i) order_[static_cast<size_t>(fill[static_cast<size_t>(cell_of[i])]++)] = static_cast<int>(i);

}

template <class F>
void PointMap::for_each_within(const Eigen::Vector2d& q, double r, F&& f) const
{
  const int cx0 = std::max(0, static_cast<int>(std::floor((q.x() - r - x0_) / cell_)));
  const int cx1 = std::min(w_ - 1, static_cast<int>(std::floor((q.x() + r - x0_) / cell_)));
  const int cy0 = std::max(0, static_cast<int>(std::floor((q.y() - r - y0_) / cell_)));
  const int cy1 = std::min(h_ - 1, static_cast<int>(std::floor((q.y() + r - y0_) / cell_)));
  const double r2 = r * r;
  for (int cy = cy0; cy <= cy1; ++cy)
    for (int cx = cx0; cx <= cx1; ++cx) {
      const size_t c = static_cast<size_t>(cy * w_ + cx);
      for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const int j = order_[static_cast<size_t>(k)];
        if ((points_[static_cast<size_t>(j)] - q).squaredNorm() <= r2) f(j);
      }
    }
}

int PointMap::nearest(const Eigen::Vector2d& q, double max_dist) const
{
  if (points_.empty()) return -1;
  int best = -1;
  double best_d2 = max_dist * max_dist;
  for_each_within(q, max_dist, [&](int j) {
    const double d2 = (points_[static_cast<size_t>(j)] - q).squaredNorm();
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = j;
    }
  });
  return best;
}

int PointMap::nearest(const Eigen::Vector2d& q, double max_dist, const Eigen::Vector2d& n, double min_cos) const
{
  if (points_.empty()) return -1;
  int best = -1;
  double best_d2 = max_dist * max_dist;
  for_each_within(q, max_dist, [&](int j) {
    if (has_normal_[static_cast<size_t>(j)] && n.dot(normals_[static_cast<size_t>(j)]) < min_cos) return;
    const double d2 = (points_[static_cast<size_t>(j)] - q).squaredNorm();
    if (d2 <= best_d2) {
      best_d2 = d2;
      best = j;
    }
  });
  return best;
}

void orient_normals_toward(const Points& points, const Eigen::Vector2d& viewpoint, Points* normals,
                           const std::vector<char>& has_normal)
{
  for (size_t i = 0; i < points.size() && i < normals->size() && i < has_normal.size(); ++i)
    if (has_normal[i] && (*normals)[i].dot(viewpoint - points[i]) < 0.0) (*normals)[i] = -(*normals)[i];
}

}  // namespace rgnav::scan_mapper
