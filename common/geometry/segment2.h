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

}  // namespace rgnav::geometry
