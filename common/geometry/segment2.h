// Segments and rays in the plane: where a ray meets a line, whether two segments cross, how far a
// point is from a segment. One copy for the kernel, the gateway detector, the simulator and the
// test worlds. The callers differ in their tolerances (a parallel test of 1e-9 or 1e-12, a
// zero-length segment or one shorter than 1e-9 m), so a tolerance is a parameter, never a
// guess: each caller keeps exactly the numbers it had. Inline: the simulator's ray caster calls
// these millions of times a run.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace rgnav::geometry {

// The z of the 3D cross product (u, 0) x (v, 0): positive when v is counter-clockwise of u.
inline double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Where the line origin + along_ray * dir meets the line a + along_line * (b - a): along_ray in
// units of |dir| (negative: behind the origin), along_line 0 at a and 1 at b.
struct RayHit
{
  double along_ray = 0.0;
  double along_line = 0.0;
};

// The meeting point of the two lines; nullopt when they are parallel, that is when
// |cross(dir, b - a)| < parallel_below (0: only when exactly parallel).
inline std::optional<RayHit> ray_meets_line(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                            const Eigen::Vector2d& a, const Eigen::Vector2d& b, double parallel_below)
{
  const Eigen::Vector2d e = b - a;
  const double denom = cross(dir, e);
  if (std::fabs(denom) < parallel_below) return std::nullopt;
  const Eigen::Vector2d ao = a - origin;
  return RayHit{cross(ao, e) / denom, cross(ao, dir) / denom};
}

// True when segments p-q and a-b cross properly: each one's ends lie strictly on both sides of
// the other's line. Touching at an end, or lying on one line, is no crossing.
inline bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b)
{
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

// The smallest squared length below which point_segment_distance treats a segment as its end
// point a: the default counts only a segment of length zero as a point.
constexpr double kZeroLength2 = std::numeric_limits<double>::denorm_min();

// Distance from p to the closest point of segment a-b; a segment whose squared length is below
// point_below_length2 counts as the point a.
inline double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                     double point_below_length2 = kZeroLength2)
{
  const Eigen::Vector2d d = b - a;
  const double length2 = d.squaredNorm();
  if (length2 < point_below_length2) return (p - a).norm();
  const double t = std::clamp((p - a).dot(d) / length2, 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Smallest distance between segments s0-s1 and t0-t1 (0 if they cross); a segment shorter than
// 1e-9 counts as a point. The line grouping's "distance" (diss. 3.1): the RG kernel's objects
// and the vision's quadrangles.
inline double segments_distance(const Eigen::Vector2d& s0, const Eigen::Vector2d& s1, const Eigen::Vector2d& t0,
                                const Eigen::Vector2d& t1)
{
  // Lines count as parallel unless |cross(s, t)| is strictly more than 1e-12.
  static const double kParallelBelow = std::nextafter(1e-12, 1.0);
  const auto hit = ray_meets_line(s0, s1 - s0, t0, t1, kParallelBelow);
  if (hit) {
    const double a = hit->along_ray, b = hit->along_line;
    if (a >= 0 && a <= 1 && b >= 0 && b <= 1) return 0;
  }
  constexpr double kPoint2 = 1e-18;
  return std::min({point_segment_distance(s0, t0, t1, kPoint2), point_segment_distance(s1, t0, t1, kPoint2),
                   point_segment_distance(t0, s0, s1, kPoint2), point_segment_distance(t1, s0, s1, kPoint2)});
}

// Gap between two non-parallel segments at the corner they would form: how far the farther of
// the two is from the intersection of their lines (0 if they really intersect; infinity if the
// lines are parallel).
inline double corner_gap(const Eigen::Vector2d& s0, const Eigen::Vector2d& s1, const Eigen::Vector2d& t0,
                         const Eigen::Vector2d& t1)
{
  const Eigen::Vector2d r = s1 - s0, q = t1 - t0;
  const auto hit = ray_meets_line(s0, r, t0, t1, 1e-12 * r.norm() * q.norm());
  if (!hit) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d x = s0 + r * hit->along_ray;
  constexpr double kPoint2 = 1e-18;
  return std::max(point_segment_distance(x, s0, s1, kPoint2), point_segment_distance(x, t0, t1, kPoint2));
}

}  // namespace rgnav::geometry
