#include "procs/rg_kernel/object_grouping.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "geometry/segment2.h"
#include "geometry/symmetric_eigen2.h"
#include "procs/rg_kernel/line_map.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;
using rgmap::LineSegment;
using rgmap::Object2d;

namespace {

using geometry::cross;

// A rectangle hypothesis: its sides (segment indices) and the rectangle they define.
struct Hypothesis
{
  std::vector<int> sides;
  double theta = 0;                 // direction of axis u
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;   // extents along u and v (region frame projections)
  double support = 0;               // [m] total length of the sides
  double inside_free = 0;
  bool valid = false;

  Vector2d u() const { return {std::cos(theta), std::sin(theta)}; }
  Vector2d v() const { return {-std::sin(theta), std::cos(theta)}; }
  Vector2d center() const { return u() * (0.5 * (u0 + u1)) + v() * (0.5 * (v0 + v1)); }
  bool contains(const Vector2d& p) const
  {
    const double pu = p.dot(u()), pv = p.dot(v());
    return pu > u0 && pu < u1 && pv > v0 && pv < v1;
  }
};

// Orientation of a set of (near-)perpendicular sides: mean of 4x the line angles, so that
// parallel and perpendicular sides vote for the same axis; weighted by length.
double common_axis(const std::vector<LineSegment>& segs, const std::vector<int>& sides)
{
  double c = 0, s = 0;
  for (const int i : sides) {
    const Vector2d d = segs[i].b - segs[i].a;
    const double a = std::atan2(d.y(), d.x()), w = d.norm();
    c += w * std::cos(4 * a);
    s += w * std::sin(4 * a);
  }
  return std::atan2(s, c) / 4;
}

// Builds the rectangle of a group of sides: each side bounds the axis across it at its own
// offset; an axis bounded by one side only is closed at the farthest end point of the group
// on the other side (the hidden side of a box seen from two or three sides).
Hypothesis make_rectangle(const std::vector<LineSegment>& segs, std::vector<int> sides, const ObjectOptions& o)
{
  Hypothesis h;
  h.sides = std::move(sides);
  h.theta = common_axis(segs, h.sides);
  const Vector2d u = h.u(), v = h.v();
  std::vector<double> bu, bv;   // offsets of sides bounding u (sides along v) and v (sides along u)
  double pu0 = std::numeric_limits<double>::max(), pu1 = -pu0, pv0 = pu0, pv1 = -pu0;
  for (const int i : h.sides) {
    const LineSegment& s = segs[i];
    const Vector2d mid = 0.5 * (s.a + s.b), d = (s.b - s.a).normalized();
    if (std::fabs(d.dot(u)) > std::fabs(d.dot(v))) bv.push_back(mid.dot(v));
    else bu.push_back(mid.dot(u));
    for (const Vector2d& p : {s.a, s.b}) {
      pu0 = std::min(pu0, p.dot(u));
      pu1 = std::max(pu1, p.dot(u));
      pv0 = std::min(pv0, p.dot(v));
      pv1 = std::max(pv1, p.dot(v));
    }
    h.support += length(s);
  }
  auto bounds = [](const std::vector<double>& b, double p0, double p1, double* lo, double* hi) {
    if (b.empty()) return false;
    const auto [mn, mx] = std::minmax_element(b.begin(), b.end());
    if (b.size() >= 2) {
      *lo = *mn;
      *hi = *mx;
    } else if (std::fabs(p0 - b[0]) > std::fabs(p1 - b[0])) {
      *lo = p0;
      *hi = b[0];
    } else {
      *lo = b[0];
      *hi = p1;
    }
    return true;
  };
  if (!bounds(bu, pu0, pu1, &h.u0, &h.u1) || !bounds(bv, pv0, pv1, &h.v0, &h.v1)) return h;
  const double lu = h.u1 - h.u0, lv = h.v1 - h.v0;
  const double max_side = h.sides.size() == 2 ? o.max_side_from_two : o.max_side;
  if (std::min(lu, lv) < o.do_min || std::max(lu, lv) > max_side) return h;
  // A side must not overhang the rectangle: a wall running past a box is not its side.
  for (const int i : h.sides) {
    for (const Vector2d& p : {segs[i].a, segs[i].b}) {
      if (p.dot(u) < h.u0 - o.dn_max || p.dot(u) > h.u1 + o.dn_max || p.dot(v) < h.v0 - o.dn_max || p.dot(v) > h.v1 + o.dn_max)
        return h;
    }
  }
  h.valid = true;
  return h;
}

bool free_at(const rgmap::FreespaceBitmap& fs, const Vector2d& p) { return fs.is_free(p); }

// Seen from outside: free cells just outside every observed side, little free inside.
bool seen_from_outside(const std::vector<LineSegment>& segs, Hypothesis* h, const rgmap::FreespaceBitmap& fs,
                       const ObjectOptions& o)
{
  const double res = fs.resolution();
  const Vector2d u = h->u(), v = h->v();
  // Inside, one cell in from the sides (wedges carved up to a face may graze its cells).
  int n = 0, nfree = 0;
  const double m = res;
  if (h->u1 - h->u0 > 2 * m && h->v1 - h->v0 > 2 * m) {
    for (double a = h->u0 + m; a <= h->u1 - m + 1e-9; a += res / 2)
      for (double b = h->v0 + m; b <= h->v1 - m + 1e-9; b += res / 2) {
        ++n;
        nfree += free_at(fs, u * a + v * b);
      }
  } else {
    n = 1;
    nfree = free_at(fs, h->center());
  }
  h->inside_free = static_cast<double>(nfree) / n;
  if (h->inside_free > o.max_inside_free) return false;
  for (const int i : h->sides) {
    const LineSegment& s = segs[i];
    const Vector2d d = (s.b - s.a).normalized();
    const bool along_u = std::fabs(d.dot(u)) > std::fabs(d.dot(v));
    const Vector2d mid = 0.5 * (s.a + s.b);
    Vector2d out;
    if (along_u) out = (mid.dot(v) > 0.5 * (h->v0 + h->v1)) ? v : Vector2d(-v);
    else out = (mid.dot(u) > 0.5 * (h->u0 + h->u1)) ? u : Vector2d(-u);
    const double len = length(s);
    const int k = std::max(2, static_cast<int>(std::ceil(len / (res / 2))));
    int probes = 0, free = 0;
    for (int j = 0; j <= k; ++j) {
      const Vector2d p = s.a + (s.b - s.a) * (static_cast<double>(j) / k) + out * o.outside_offset;
      ++probes;
      free += free_at(fs, p);
    }
    if (static_cast<double>(free) / probes < o.min_outside_free) return false;
  }
  return true;
}

Object2d to_object(const Hypothesis& h, double confidence)
{
  const double lu = h.u1 - h.u0, lv = h.v1 - h.v0;
  double theta = lu >= lv ? h.theta : h.theta + M_PI / 2;
  while (theta > M_PI / 2) theta -= M_PI;
  while (theta <= -M_PI / 2) theta += M_PI;
  const Vector2d c = h.center();
  Object2d obj;
  obj.shape = Object2d::Shape::kRectangle;
  obj.center = geometry::Pose2(c.x(), c.y(), theta);
  obj.length = std::max(lu, lv);
  obj.width = std::min(lu, lv);
  obj.confidence = confidence;
  return obj;
}

}  // namespace

double segment_distance(const LineSegment& s, const LineSegment& t) { return geometry::segments_distance(s.a, s.b, t.a, t.b); }

double corner_gap(const LineSegment& s, const LineSegment& t) { return geometry::corner_gap(s.a, s.b, t.a, t.b); }

std::vector<Object2d> group_rectangles(const std::vector<LineSegment>& segs, const rgmap::FreespaceBitmap& fs,
                                       const ObjectOptions& o)
{
  std::vector<Object2d> out;
  if (!o.enabled || fs.width() == 0 || segs.size() < 2) return out;
  const int n = static_cast<int>(segs.size());
  // Stage 1 (diss. Fig. 3.2): corners — pairs meeting at alpha_min..alpha_max within DN_max.
  const double min_corner = std::min(o.alpha_min, M_PI - o.alpha_max);   // smaller intersection angle
  std::vector<std::vector<int>> adj(static_cast<size_t>(n));
  std::vector<std::vector<bool>> corner(static_cast<size_t>(n), std::vector<bool>(static_cast<size_t>(n), false));
  const double max_cos = std::cos(min_corner);
  std::vector<Vector2d> dir(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) dir[i] = length(segs[i]) < 1e-6 ? Vector2d::Zero() : Vector2d((segs[i].b - segs[i].a).normalized());
  for (int i = 0; i < n; ++i) {
    if (dir[i].isZero()) continue;
    for (int j = i + 1; j < n; ++j) {
      if (dir[j].isZero() || std::fabs(dir[i].dot(dir[j])) > max_cos) continue;
      if (corner_gap(segs[i], segs[j]) >= o.dn_max) continue;
      corner[i][j] = corner[j][i] = true;
      adj[i].push_back(j);
      adj[j].push_back(i);
    }
  }
  // Stage 2: pairs of corners closing four sides (restrictive: every side is a direct
  // neighbour of both of its neighbours; opposite sides farther apart than DO_min).
  std::vector<Hypothesis> hyps;
  std::set<std::vector<int>> seen;
  // Noisy maps keep many near-parallel pieces of one wall, and every pair of them with a crossing
  // wall is a corner: bound the work (deterministically) so a region's description stays cheap.
  int64_t budget = o.max_hypotheses;
  auto add = [&](std::vector<int> sides) {
    if (budget <= 0) return;
    --budget;
    std::vector<int> key = sides;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) return;
    Hypothesis h = make_rectangle(segs, std::move(sides), o);
    if (h.valid && seen_from_outside(segs, &h, fs, o)) hyps.push_back(std::move(h));
  };
  for (int i = 0; i < n; ++i)
    for (const int j : adj[i])
      for (const int k : adj[j]) {
        if (k == i || corner[i][k]) continue;
        if (segment_distance(segs[i], segs[k]) <= o.do_min) continue;
        for (const int l : adj[k]) {
          if (l == j || l == i || !corner[l][i] || corner[j][l]) continue;
          if (segment_distance(segs[j], segs[l]) <= o.do_min) continue;
          add({i, j, k, l});
        }
        // Three sides i-j-k, both i and k on the same side of j: the fourth is hidden.
        if (o.complete_three_sides) {
          const Vector2d dj = (segs[j].b - segs[j].a).normalized();
          auto far_side = [&](const LineSegment& s) {
            const double a = cross(dj, s.a - segs[j].a), b = cross(dj, s.b - segs[j].a);
            return std::fabs(a) > std::fabs(b) ? a : b;
          };
          if (i < k && far_side(segs[i]) * far_side(segs[k]) > 0) add({i, j, k});
        }
      }
  if (o.complete_two_sides)
    for (int i = 0; i < n; ++i)
      for (const int j : adj[i])
        if (i < j) add({i, j});
  // Keep the best of overlapping hypotheses: more observed sides first, then more support.
  std::sort(hyps.begin(), hyps.end(), [](const Hypothesis& a, const Hypothesis& b) {
    if (a.sides.size() != b.sides.size()) return a.sides.size() > b.sides.size();
    if (a.support != b.support) return a.support > b.support;
    return a.sides < b.sides;
  });
  std::vector<const Hypothesis*> kept;
  for (const Hypothesis& h : hyps) {
    bool overlaps = false;
    for (const Hypothesis* k : kept)
      if (k->contains(h.center()) || h.contains(k->center())) overlaps = true;
    if (overlaps) continue;
    kept.push_back(&h);
    out.push_back(to_object(h, (static_cast<double>(h.sides.size()) / 4.0) * (1.0 - h.inside_free)));
  }
  return out;
}

std::vector<CircleObservation> circles_in_scan(const ScanPoints& scan, const ObjectOptions& o)
{
  std::vector<CircleObservation> out;
  if (!o.enabled || !o.circles) return out;
  const auto& p = scan.points;
  const size_t n = p.size();
  size_t start = 0;
  for (size_t end = 1; end <= n; ++end) {
    if (end < n && (p[end] - p[end - 1]).norm() <= o.arc_point_gap) continue;
    const size_t first = start, last = end - 1;
    start = end;
    if (last + 1 < first + static_cast<size_t>(o.arc_min_points)) continue;
    if ((p[last] - p[first]).norm() > 2 * o.circle_max_radius) continue;
    // Free-standing: the neighbouring points (if any) lie well behind the arc.
    double nearest = std::numeric_limits<double>::max();
    for (size_t i = first; i <= last; ++i) nearest = std::min(nearest, (p[i] - scan.origin).norm());
    if (first > 0 && (p[first - 1] - scan.origin).norm() < nearest + o.arc_depth_jump) continue;
    if (last + 1 < n && (p[last + 1] - scan.origin).norm() < nearest + o.arc_depth_jump) continue;
    // Algebraic circle fit (Kasa) about the centroid: x^2 + y^2 + D x + E y + F = 0.
    Vector2d c0 = Vector2d::Zero();
    for (size_t i = first; i <= last; ++i) c0 += p[i];
    c0 /= static_cast<double>(last - first + 1);
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (size_t i = first; i <= last; ++i) {
      const Vector2d q = p[i] - c0;
      const Eigen::Vector3d row(q.x(), q.y(), 1.0);
      A += row * row.transpose();
      b -= row * q.squaredNorm();
      cov += q * q.transpose();
    }
    const Eigen::Vector3d def = A.ldlt().solve(b);
    if (!def.allFinite()) continue;
    const Vector2d c(-def(0) / 2, -def(1) / 2);
    const double r2 = c.squaredNorm() - def(2);
    if (r2 <= 0) continue;
    const double r = std::sqrt(r2);
    if (r < o.circle_min_radius || r > o.circle_max_radius) continue;
    double ss = 0;
    for (size_t i = first; i <= last; ++i) ss += std::pow((p[i] - c0 - c).norm() - r, 2);
    const double m = static_cast<double>(last - first + 1);
    const double rms = std::sqrt(ss / m);
    // A line must fit clearly worse (a flat piece is not an arc).
    const double line_sigma = std::sqrt(std::max(0.0, geometry::symmetric_eigen(cov / m).values(0)));
    if (rms > o.circle_max_rms || line_sigma < 2 * rms || line_sigma < 0.003) continue;
    const Vector2d center = c0 + c;
    // Convex towards the laser: the centre lies behind the arc.
    if ((center - scan.origin).norm() <= nearest) continue;
    out.push_back({center, r});
  }
  return out;
}

std::vector<Object2d> cluster_circles(const std::vector<CircleObservation>& obs, const rgmap::FreespaceBitmap& fs,
                                      const ObjectOptions& o)
{
  struct Cluster
  {
    Vector2d sum{0, 0};
    double rsum = 0;
    int n = 0;
    Vector2d center() const { return sum / n; }
    double radius() const { return rsum / n; }
  };
  std::vector<Cluster> clusters;
  for (const auto& ob : obs) {
    Cluster* best = nullptr;
    double best_d = std::numeric_limits<double>::max();
    for (auto& c : clusters) {
      const double d = (c.center() - ob.center).norm();
      if (d < std::max(0.05, 0.5 * c.radius()) && d < best_d) {
        best = &c;
        best_d = d;
      }
    }
    if (!best) {
      clusters.push_back({});
      best = &clusters.back();
    }
    best->sum += ob.center;
    best->rsum += ob.radius;
    ++best->n;
  }
  std::sort(clusters.begin(), clusters.end(), [](const Cluster& a, const Cluster& b) { return a.n > b.n; });
  std::vector<Object2d> out;
  std::vector<Cluster> kept;
  for (const auto& c : clusters) {
    if (c.n < o.circle_min_scans) break;
    const Vector2d x = c.center();
    const double r = c.radius();
    if (fs.width() > 0) {
      if (fs.is_free(x)) continue;
      // Seen from the region: part of a ring just outside the circle is free space.
      int free = 0;
      for (int k = 0; k < 24; ++k) {
        const double a = k * M_PI / 12;
        free += fs.is_free(x + (r + o.outside_offset) * Vector2d(std::cos(a), std::sin(a)));
      }
      if (free < 6) continue;
    }
    bool overlaps = false;
    for (const auto& k : kept) overlaps |= (k.center() - x).norm() < k.radius() + r;
    if (overlaps) continue;
    kept.push_back(c);
    Object2d obj;
    obj.shape = Object2d::Shape::kCircle;
    obj.center = geometry::Pose2(x.x(), x.y(), 0.0);
    obj.length = obj.width = 2 * r;
    obj.confidence = std::min(1.0, static_cast<double>(c.n) / (3.0 * o.circle_min_scans));
    out.push_back(obj);
  }
  return out;
}

std::vector<Object2d> find_objects(int64_t region_id, const std::vector<LineSegment>& segments,
                                   const std::vector<CircleObservation>& circle_observations, const rgmap::FreespaceBitmap& freespace,
                                   const ObjectOptions& o)
{
  std::vector<Object2d> out;
  if (!o.enabled) return out;
  out = group_rectangles(segments, freespace, o);
  const size_t rects = out.size();
  for (const Object2d& c : cluster_circles(circle_observations, freespace, o)) {
    // An arc on a box's corner is part of the box.
    bool inside = false;
    for (size_t k = 0; k < rects; ++k) {
      const Vector2d d = out[k].center.inverse() * c.center.translation();
      inside |= std::fabs(d.x()) <= out[k].length / 2 && std::fabs(d.y()) <= out[k].width / 2;
    }
    if (!inside) out.push_back(c);
  }
  for (size_t k = 0; k < out.size() && k < 999; ++k) out[k].id = region_id * 1000 + static_cast<int64_t>(k) + 1;
  if (out.size() > 999) out.resize(999);
  return out;
}

}  // namespace rgnav::rg_kernel
