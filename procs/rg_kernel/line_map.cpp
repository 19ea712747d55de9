#include "procs/rg_kernel/line_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/symmetric_eigen2.h"

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
  const geometry::SymmetricEigen2 es = geometry::symmetric_eigen(cov / n);
  f.direction = es.vectors.col(1);
  f.sigma = std::sqrt(std::max(0.0, es.values(0)));
  return f;
}

double point_line_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b)
{
  const Vector2d d = b - a;
  const double len = d.norm();
  if (len < 1e-12) return (p - a).norm();
  return std::fabs(d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x())) / len;
}

void split(const std::vector<Vector2d>& pts, size_t first, size_t last, const ExtractOptions& o, double split_distance,
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
  if (worst_d > split_distance) {
    split(pts, first, worst, o, split_distance, out);
    split(pts, worst, last, o, split_distance, out);
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

// A segment as the points behind it: `support` points spread evenly from a to b, scattered
// by sigma across the line. Segments carry no more than that, and it is enough to fit the
// common line of several segments by total least squares with each weighted by its support,
// so that a wall seen by many scans ends on the mean of its observations rather than on the
// two end points that happen to lie farthest apart.
struct Moments
{
  double n = 0;
  Vector2d mean = Vector2d::Zero();
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();   // about the mean, summed over the points
};

Moments moments_of(const LineSegment& s)
{
  Moments m;
  m.n = std::max(1, s.support);
  m.mean = 0.5 * (s.a + s.b);
  const Vector2d d = s.b - s.a;
  const double len = d.norm();
  const Vector2d u = len > 1e-12 ? Vector2d(d / len) : Vector2d(1, 0);
  const Vector2d v(-u.y(), u.x());
  m.scatter = m.n * (len * len / 12.0 * u * u.transpose() + s.sigma * s.sigma * v * v.transpose());
  return m;
}

Moments combined(const Moments& a, const Moments& b)
{
  Moments m;
  m.n = a.n + b.n;
  m.mean = (a.n * a.mean + b.n * b.mean) / m.n;
  const Vector2d da = a.mean - m.mean, db = b.mean - m.mean;
  m.scatter = a.scatter + b.scatter + a.n * da * da.transpose() + b.n * db * db.transpose();
  return m;
}

// The common line of two segments: support-weighted total least squares over their points.
struct CommonLine
{
  Vector2d point;
  Vector2d dir;     // unit
  double sigma = 0;
  double offset(const Vector2d& p) const { return std::fabs(dir.x() * (p.y() - point.y()) - dir.y() * (p.x() - point.x())); }
  double along(const Vector2d& p) const { return dir.dot(p - point); }
};

CommonLine common_line(const LineSegment& a, const LineSegment& b)
{
  const Moments m = combined(moments_of(a), moments_of(b));
  const geometry::SymmetricEigen2 es = geometry::symmetric_eigen(m.scatter / m.n);
  return {m.mean, es.vectors.col(1), std::sqrt(std::max(0.0, es.values(0)))};
}

// The angle two segments may differ by: alpha_max, or for a short segment the angle its end
// points can swing through within D_L^max of the line — its direction is known no better, and
// the distance test below then decides.
double angle_tolerance(const LineSegment& a, const LineSegment& b, const MergeOptions& o)
{
  const double shorter = std::min(length(a), length(b));
  if (shorter < 1e-9) return M_PI / 2;
  return std::max(o.alpha_max, std::atan2(2.0 * o.dl_max, shorter));
}

struct MergeTest
{
  bool ok = false;
  double dl = 0;   // D_L against the common line
};

// The dissertation's tests (3.1.1). D_L: the mean distance of one segment's end points to the
// other's line, taken in the direction that relies on the better known line — the dissertation
// averages both directions, which measures a long wall's far end points against the extended
// line of a short, noisy piece of it and refuses the merge. For parallel segments both
// directions give the offset between them. Then the two must overlap along their common line
// or leave a gap below D_gap^max.
MergeTest test_merge(const LineSegment& a, const LineSegment& b, const CommonLine& line, const MergeOptions& o)
{
  MergeTest t;
  const double a_to_b = 0.5 * (point_line_distance(a.a, b.a, b.b) + point_line_distance(a.b, b.a, b.b));
  const double b_to_a = 0.5 * (point_line_distance(b.a, a.a, a.b) + point_line_distance(b.b, a.a, a.b));
  t.dl = std::min(a_to_b, b_to_a);
  if (t.dl > o.dl_max) return t;
  double a0 = line.along(a.a), a1 = line.along(a.b), b0 = line.along(b.a), b1 = line.along(b.b);
  if (a0 > a1) std::swap(a0, a1);
  if (b0 > b1) std::swap(b0, b1);
  const double gap = std::max(b0 - a1, a0 - b1);  // < 0 when they overlap
  t.ok = gap <= o.gap_max;
  return t;
}

// The merged segment: on the common line, from the farthest to the farthest projected end point.
LineSegment merged(const LineSegment& a, const LineSegment& b, const CommonLine& line)
{
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const Vector2d& p : {a.a, a.b, b.a, b.b}) {
    lo = std::min(lo, line.along(p));
    hi = std::max(hi, line.along(p));
  }
  LineSegment m;
  m.a = line.point + lo * line.dir;
  m.b = line.point + hi * line.dir;
  m.sigma = line.sigma;
  m.support = a.support + b.support;
  return m;
}

// Merges b into a if the two qualify; true if merged.
bool try_merge(LineSegment* a, const LineSegment& b, const MergeOptions& o)
{
  if (angle_difference(angle_of(*a), angle_of(b)) > angle_tolerance(*a, b, o)) return false;
  const CommonLine line = common_line(*a, b);
  if (!test_merge(*a, b, line, o).ok) return false;
  *a = merged(*a, b, line);
  return true;
}

}  // namespace

double line_distance(const LineSegment& a, const LineSegment& b)
{
  return 0.25 * (point_line_distance(a.a, b.a, b.b) + point_line_distance(a.b, b.a, b.b) +
                 point_line_distance(b.a, a.a, a.b) + point_line_distance(b.b, a.a, a.b));
}

double estimate_range_noise(const std::vector<Vector2d>& points, double max_point_gap)
{
  std::vector<double> d;
  d.reserve(points.size());
  for (size_t i = 1; i + 1 < points.size(); ++i) {
    const Vector2d &a = points[i - 1], &b = points[i], &c = points[i + 1];
    if ((b - a).norm() > max_point_gap || (c - b).norm() > max_point_gap || (c - a).norm() < 1e-9) continue;
    d.push_back(point_line_distance(b, a, c));
  }
  constexpr size_t kMinTriples = 10;
  if (d.size() < kMinTriples) return 0.0;
  // Corners and depth edges are the outliers the median ignores; 1.4826: MAD to sigma for
  // Gaussian noise; sqrt(1.5): a point's offset from its neighbours' chord has variance 1.5 sigma^2.
  auto mid = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), mid, d.end());
  return *mid * 1.4826 / std::sqrt(1.5);
}

std::vector<LineSegment> extract_segments(const std::vector<Vector2d>& points, const ExtractOptions& o, double range_noise)
{
  const double split_distance = std::max(o.split_distance, o.noise_split_factor * range_noise);
  std::vector<LineSegment> out;
  size_t start = 0;
  for (size_t i = 1; i <= points.size(); ++i) {
    if (i == points.size() || (points[i] - points[i - 1]).norm() > o.max_point_gap) {
      if (i > start) split(points, start, i - 1, o, split_distance, &out);
      start = i;
    }
  }
  return out;
}

namespace {

MergeOptions with_noise(MergeOptions o, double range_noise)
{
  o.dl_max = std::max(o.dl_max, o.noise_dl_factor * range_noise);
  return o;
}

}  // namespace

std::vector<LineSegment> merge_segments(std::vector<LineSegment> segs, const MergeOptions& options, double range_noise)
{
  const MergeOptions o = with_noise(options, range_noise);
  // Pairwise with a cheap angle test first. The dissertation sorts by angle and compares
  // within an angle window to get O(N); a region map holds a few hundred segments at most
  // while merging (one scan adds ~10-20 to a map of ~40), where the plain loop is fast enough
  // and obviously right, including the wrap-around of line angles at pi.
  std::vector<bool> gone(segs.size(), false);
  bool merged_any = true;
  while (merged_any) {
    merged_any = false;
    for (size_t i = 0; i < segs.size(); ++i) {
      if (gone[i]) continue;
      for (size_t j = i + 1; j < segs.size(); ++j) {
        if (gone[j]) continue;
        if (try_merge(&segs[i], segs[j], o)) {
          gone[j] = true;
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

std::vector<LineSegment> merge_into(std::vector<LineSegment> map, std::vector<LineSegment> fresh, const MergeOptions& options,
                                    double range_noise, const geometry::Pose2* pose_error)
{
  const MergeOptions fresh_o = with_noise(options, range_noise);
  std::vector<double> angle(map.size());
  for (size_t i = 0; i < map.size(); ++i) angle[i] = angle_of(map[i]);
  for (LineSegment cur : merge_segments(std::move(fresh), fresh_o)) {
    MergeOptions o = fresh_o;
    if (pose_error) o.dl_max += std::max(((*pose_error) * cur.a - cur.a).norm(), ((*pose_error) * cur.b - cur.b).norm());
    // Merge with the map segment that lies best on the common line (smallest D_L), then try
    // the grown segment again: it may now bridge to a neighbour (merges cascade).
    for (;;) {
      const double cur_angle = angle_of(cur);
      size_t best = map.size();
      double best_dl = std::numeric_limits<double>::max();
      CommonLine best_line;
      for (size_t i = 0; i < map.size(); ++i) {
        if (angle_difference(angle[i], cur_angle) > angle_tolerance(map[i], cur, o)) continue;
        const CommonLine line = common_line(map[i], cur);
        const MergeTest t = test_merge(map[i], cur, line, o);
        if (t.ok && t.dl < best_dl) {
          best = i;
          best_dl = t.dl;
          best_line = line;
        }
      }
      if (best == map.size()) break;
      cur = merged(map[best], cur, best_line);
      map[best] = map.back();
      angle[best] = angle.back();
      map.pop_back();
      angle.pop_back();
    }
    map.push_back(cur);
    angle.push_back(angle_of(cur));
  }
  return map;
}

}  // namespace rgnav::rg_kernel
