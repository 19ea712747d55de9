#include "rgmap/freespace_bitmap.h"

#include <cmath>
#include <stdexcept>

#include "geometry/symmetric_eigen2.h"

namespace rgnav::rgmap {

FreespaceBitmap::FreespaceBitmap(double resolution, geometry::Pose2 region_from_grid, int width, int height)
    : resolution_(resolution), region_from_grid_(region_from_grid), width_(width), height_(height),
      bytes_((static_cast<size_t>(width) * static_cast<size_t>(height) + 7) / 8, 0)
{
  if (!(resolution > 0) || width < 0 || height < 0) throw std::invalid_argument("freespace bitmap: bad geometry");
}

FreespaceBitmap::FreespaceBitmap(double resolution, geometry::Pose2 region_from_grid, int width, int height,
                                 std::vector<uint8_t> bytes)
    : FreespaceBitmap(resolution, region_from_grid, width, height)
{
  if (bytes.size() != bytes_.size()) throw std::invalid_argument("freespace bitmap: byte count != ceil(w*h/8)");
  bytes_ = std::move(bytes);
}

bool FreespaceBitmap::free(int cx, int cy) const
{
  if (!in_bounds(cx, cy)) return false;
  const size_t i = static_cast<size_t>(cy) * static_cast<size_t>(width_) + static_cast<size_t>(cx);
  return (bytes_[i / 8] >> (i % 8)) & 1u;
}

void FreespaceBitmap::set_free(int cx, int cy, bool is_free)
{
  if (!in_bounds(cx, cy)) return;
  const size_t i = static_cast<size_t>(cy) * static_cast<size_t>(width_) + static_cast<size_t>(cx);
  const auto bit = static_cast<uint8_t>(1u << (i % 8));
  if (is_free) bytes_[i / 8] |= bit;
  else bytes_[i / 8] &= static_cast<uint8_t>(~bit);
}

bool FreespaceBitmap::cell_of(const Eigen::Vector2d& p, int* cx, int* cy) const
{
  const Eigen::Vector2d g = region_from_grid_.inverse() * p;
  const double fx = std::floor(g.x() / resolution_), fy = std::floor(g.y() / resolution_);
  if (fx < 0 || fy < 0 || fx >= width_ || fy >= height_) return false;
  *cx = static_cast<int>(fx);
  *cy = static_cast<int>(fy);
  return true;
}

bool FreespaceBitmap::is_free(const Eigen::Vector2d& p) const
{
  int cx = 0, cy = 0;
  return cell_of(p, &cx, &cy) && free(cx, cy);
}

void FreespaceBitmap::carve_ray(const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool exclude_end)
{
  // Sample at a quarter cell: simple, and exact enough for a 1-bit map.
  const double len = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(len / (0.25 * resolution_))));
  int end_x = -1, end_y = -1;
  if (exclude_end) cell_of(b, &end_x, &end_y);
  for (int k = 0; k <= steps; ++k) {
    int cx = 0, cy = 0;
    if (!cell_of(a + (b - a) * (static_cast<double>(k) / steps), &cx, &cy)) continue;
    if (exclude_end && cx == end_x && cy == end_y) continue;
    set_free(cx, cy, true);
  }
}

int FreespaceBitmap::free_cells() const
{
  int n = 0;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) n += free(x, y) ? 1 : 0;
  return n;
}

FreespaceFeatures FreespaceBitmap::features() const
{
  FreespaceFeatures f;
  const double cell_area = resolution_ * resolution_;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_sq = Eigen::Matrix2d::Zero();
  int n = 0;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      if (!free(x, y)) continue;
      const Eigen::Vector2d c = region_from_grid_ * Eigen::Vector2d((x + 0.5) * resolution_, (y + 0.5) * resolution_);
      sum += c;
      sum_sq += c * c.transpose();
      ++n;
    }
  }
  if (n == 0) return f;
  f.area = n * cell_area;
  f.centroid = sum / n;
  f.second_moments = sum_sq / n - f.centroid * f.centroid.transpose();
  const Eigen::Vector2d ev = geometry::symmetric_eigen(f.second_moments).values.cwiseMax(0.0);  // ascending
  f.main_axes = Eigen::Vector2d(2 * std::sqrt(ev(1)), 2 * std::sqrt(ev(0)));
  return f;
}

}  // namespace rgnav::rgmap
