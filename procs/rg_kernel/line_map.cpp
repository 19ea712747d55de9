#include "procs/rg_kernel/line_map.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace rgnav::rg_kernel {
namespace {

using rgmap::LineSegment;
using Eigen::Vector2d;

struct Fit
{
  Vector2d centroid;
  Vector2d direction;   // unit
  double sigma = 0;
};

// Total least squares line through points[first, last].
Fit fit_line(const std::vector<Vector2d>& pts, size_t first, size_t last)
{
  Fit f;
  const double n = static_cast<double>(last - first + 1);
  f.centroid.setZero();
  for (size_t i = first; i <= last; ++i) f.centroid += pts[i];
  f.centroid /= n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (size_t i = first; i <= last; ++i) {
    const Vector2d d = pts[i] - f.centroid;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov / n);
  f.direction = es.eigenvectors().col(1);
  f.sigma = std::sqrt(std::max(0.0, es.eigenvalues()(0)));
  return f;
}

double point_line_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b)
{
  const Vector2d d = b - a;
  const double len = d.norm();
  if (len < 1e-12) return (p - a).norm();
  return std::fabs(d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x())) / len;
}

void split(const std::vector<Vector2d>& pts, size_t first, size_t last, const ExtractOptions& o,
           std::vector<LineSegment>* out)
{
  if (last + 1 < first + static_cast<size_t>(o.min_points)) return;
  // Split at the point farthest from the chord (iterative end-point fit).
  size_t worst = first;
  double worst_d = 0;
  for (size_t i = first + 1; i < last; ++i) {
    const double d = point_line_distance(pts[i], pts[first], pts[last]);
    if (d > worst_d) {
      worst_d = d;
      worst = i;
    }
  }
  if (worst_d > o.split_distance) {
    split(pts, first, worst, o, out);
    split(pts, worst, last, o, out);
    return;
  }
  const Fit f = fit_line(pts, first, last);
  // End points: the extreme points projected onto the fitted line.
  const Vector2d a = f.centroid + f.direction * f.direction.dot(pts[first] - f.centroid);
  const Vector2d b = f.centroid + f.direction * f.direction.dot(pts[last] - f.centroid);
  if ((b - a).norm() < o.min_length) return;
  out->push_back({a, b, f.sigma, static_cast<int>(last - first + 1)});
}

double angle_of(const LineSegment& s)
{
  // Undirected line angle in [0, pi).
  double a = std::atan2(s.b.y() - s.a.y(), s.b.x() - s.a.x());
  if (a < 0) a += M_PI;
  if (a >= M_PI) a -= M_PI;
  return a;
}

double angle_difference(double a, double b)
{
  const double d = std::fabs(a - b);
  return std::min(d, M_PI - d);
}

// Tries to merge b into a; true if merged.
bool try_merge(LineSegment* a, const LineSegment& b, const MergeOptions& o)
{
  if (angle_difference(angle_of(*a), angle_of(b)) > o.alpha_max) return false;
  if (line_distance(*a, b) > o.dl_max) return false;
  // Positions of all four end points along a's direction.
  const Vector2d dir = (a->b - a->a).normalized();
  const double a0 = 0, a1 = (a->b - a->a).dot(dir);
  double b0 = (b.a - a->a).dot(dir), b1 = (b.b - a->a).dot(dir);
  if (b0 > b1) std::swap(b0, b1);
  const double gap = std::max(b0 - a1, a0 - b1);  // < 0 when they overlap
  if (gap > o.gap_max) return false;
  // The new segment spans the two end points farthest apart.
  const Vector2d pts[4] = {a->a, a->b, b.a, b.b};
  double best = -1;
  Vector2d p = a->a, q = a->b;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if ((pts[i] - pts[j]).squaredNorm() > best) {
        best = (pts[i] - pts[j]).squaredNorm();
        p = pts[i];
        q = pts[j];
      }
  const double wa = a->support, wb = b.support;
  a->sigma = wa + wb > 0 ? std::sqrt((wa * a->sigma * a->sigma + wb * b.sigma * b.sigma) / (wa + wb)) : 0;
  a->support += b.support;
  a->a = p;
  a->b = q;
  return true;
}

}  // namespace

double line_distance(const LineSegment& a, const LineSegment& b)
{
  return 0.25 * (point_line_distance(a.a, b.a, b.b) + point_line_distance(a.b, b.a, b.b) +
                 point_line_distance(b.a, a.a, a.b) + point_line_distance(b.b, a.a, a.b));
}

std::vector<LineSegment> extract_segments(const std::vector<Vector2d>& points, const ExtractOptions& o)
{
  std::vector<LineSegment> out;
  size_t start = 0;
  for (size_t i = 1; i <= points.size(); ++i) {
    if (i == points.size() || (points[i] - points[i - 1]).norm() > o.max_point_gap) {
      if (i > start) split(points, start, i - 1, o, &out);
      start = i;
    }
  }
  return out;
}

std::vector<LineSegment> merge_segments(std::vector<LineSegment> segs, const MergeOptions& o)
{
  // Pairwise with a cheap angle test first. The dissertation sorts by angle and compares
  // within an angle window to get O(N); a region map holds a few hundred segments at most
  // while merging (one scan adds ~10-20 to a map of ~40), where the plain loop is fast enough
  // and obviously right, including the wrap-around of line angles at pi.
  std::vector<double> angle(segs.size());
  for (size_t i = 0; i < segs.size(); ++i) angle[i] = angle_of(segs[i]);
  std::vector<bool> gone(segs.size(), false);
  bool merged_any = true;
  while (merged_any) {
    merged_any = false;
    for (size_t i = 0; i < segs.size(); ++i) {
      if (gone[i]) continue;
      for (size_t j = i + 1; j < segs.size(); ++j) {
        if (gone[j] || angle_difference(angle[i], angle[j]) > o.alpha_max) continue;
        if (try_merge(&segs[i], segs[j], o)) {
          gone[j] = true;
          angle[i] = angle_of(segs[i]);
          merged_any = true;
        }
      }
    }
  }
  std::vector<LineSegment> kept;
  for (size_t i = 0; i < segs.size(); ++i)
    if (!gone[i]) kept.push_back(segs[i]);
  return kept;
}

std::vector<LineSegment> merge_into(std::vector<LineSegment> map, std::vector<LineSegment> fresh, const MergeOptions& o)
{
  for (LineSegment cur : merge_segments(std::move(fresh), o)) {
    bool merged = true;
    while (merged) {
      merged = false;
      for (size_t i = 0; i < map.size(); ++i) {
        if (angle_difference(angle_of(map[i]), angle_of(cur)) > o.alpha_max) continue;
        LineSegment grown = map[i];
        if (!try_merge(&grown, cur, o)) continue;
        cur = grown;
        map[i] = map.back();
        map.pop_back();
        merged = true;
        break;
      }
    }
    map.push_back(cur);
  }
  return map;
}

}  // namespace rgnav::rg_kernel
