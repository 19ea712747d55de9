#include "procs/rg_kernel/line_map_fidelity.h"

#include <algorithm>
#include <cmath>

#include "geometry/segment2.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

void LineMapFidelity::add(const LineMapFidelity& other)
{
  points += other.points;
  explained += other.explained;
  sum_distance += other.sum_distance;
}

double point_segment_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b)
{
  return geometry::point_segment_distance(p, a, b, 1e-24);
}

SegmentIndex::SegmentIndex(const std::vector<rgmap::LineSegment>& segments, double cap)
    : segments_(segments), cap_(cap), cell_(std::max(cap, 1e-3))
{
  // Every cell a segment passes through, exactly: per column of cells, the rows the segment
  // spans inside that column's slab. A segment within `cap` of a point then passes through one
  // of the 3 x 3 cells around the point's cell (cells are `cap` wide).
  for (size_t i = 0; i < segments_.size(); ++i) {
    Vector2d a = segments_[i].a, b = segments_[i].b;
    if (a.x() > b.x()) std::swap(a, b);
    const int64_t x0 = static_cast<int64_t>(std::floor(a.x() / cell_)), x1 = static_cast<int64_t>(std::floor(b.x() / cell_));
    if (x1 - x0 > 100000) continue;   // absurd coordinates: not indexed (never nearest)
    for (int64_t x = x0; x <= x1; ++x) {
      const double lo = std::max(a.x(), x * cell_), hi = std::min(b.x(), (x + 1) * cell_);
      const double run = b.x() - a.x();
      const double ya = run < 1e-12 ? a.y() : a.y() + (b.y() - a.y()) * (lo - a.x()) / run;
      const double yb = run < 1e-12 ? b.y() : a.y() + (b.y() - a.y()) * (hi - a.x()) / run;
      const int64_t y0 = static_cast<int64_t>(std::floor(std::min(ya, yb) / cell_));
      const int64_t y1 = static_cast<int64_t>(std::floor(std::max(ya, yb) / cell_));
      for (int64_t y = y0; y <= y1 && y - y0 <= 100000; ++y) cells_.emplace_back(key(x, y), static_cast<int32_t>(i));
    }
  }
  std::sort(cells_.begin(), cells_.end());
  cells_.erase(std::unique(cells_.begin(), cells_.end()), cells_.end());
}

int64_t SegmentIndex::key(int64_t x, int64_t y) const
{
  // 32 bits per axis: +-2^31 cells of >= 1 mm, far beyond any region.
  return (static_cast<int64_t>(static_cast<uint32_t>(x)) << 32) | static_cast<uint32_t>(y);
}

double SegmentIndex::nearest_distance(const Vector2d& p) const
{
  double d = cap_;
  nearest(p, &d);
  return d;
}

int SegmentIndex::nearest(const Vector2d& p, double* distance) const
{
  const int64_t cx = static_cast<int64_t>(std::floor(p.x() / cell_)), cy = static_cast<int64_t>(std::floor(p.y() / cell_));
  double best = cap_;
  int best_i = -1;
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy) {
      const int64_t k = key(cx + dx, cy + dy);
      auto it = std::lower_bound(cells_.begin(), cells_.end(), std::make_pair(k, int32_t{-1}));
      for (; it != cells_.end() && it->first == k; ++it) {
        const auto& s = segments_[static_cast<size_t>(it->second)];
        const double d = point_segment_distance(p, s.a, s.b);
        if (d < best || (d == best && best_i >= 0 && it->second < best_i)) {
          best = d;
          best_i = it->second;
        }
      }
    }
  if (distance) *distance = best;
  return best_i;
}

LineMapFidelity measure_fidelity(const std::vector<Vector2d>& points, const std::vector<rgmap::LineSegment>& segments,
                                 double tolerance, double cap)
{
  LineMapFidelity f;
  f.tolerance = tolerance;
  f.cap = cap;
  const SegmentIndex index(segments, cap);
  for (const Vector2d& p : points) {
    const double d = index.nearest_distance(p);
    ++f.points;
    f.sum_distance += d;
    if (d <= tolerance) ++f.explained;
  }
  return f;
}

}  // namespace rgnav::rg_kernel
