#include "procs/rg_kernel/gateway_geometry.h"

#include <algorithm>
#include <cmath>

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

// [m] an origin this far beside the ends of a side still counts as beyond it (a robot leaving a
// junction diagonally, pose noise).
constexpr double kSideMargin = 0.5;

}  // namespace

std::vector<Line> gateway_edges(const std::vector<Vector2d>& points) { return rgmap::gateway_edges(points); }

bool EdgeFrame::just_beyond(const Vector2d& p, double reach, double min_depth) const
{
  const double depth = normal.dot(p - mid);
  return depth > 0 && depth >= min_depth && depth < reach && std::fabs(along.dot(p - mid)) < 0.5 * length + kSideMargin;
}

std::vector<EdgeFrame> edge_frames(const std::vector<Vector2d>& points)
{
  Vector2d centre = Vector2d::Zero();
  for (const auto& q : points) centre += q;
  if (!points.empty()) centre /= static_cast<double>(points.size());
  std::vector<EdgeFrame> out;
  for (const auto& [a, b] : gateway_edges(points)) {
    EdgeFrame e;
    e.line = {a, b};
    e.length = (b - a).norm();
    if (e.length < 1e-6) continue;
    e.along = (b - a) / e.length;
    e.normal = Vector2d(-e.along.y(), e.along.x());
    e.mid = 0.5 * (a + b);
    if (points.size() == 4 && e.normal.dot(centre - e.mid) > 0) e.normal = -e.normal;  // outward
    out.push_back(e);
  }
  return out;
}

bool line_on_crossed_side(const std::vector<Vector2d>& outline, const Vector2d& p, const Vector2d& q, double heading,
                          double tolerance)
{
  if (outline.size() != 4) return false;
  const double len = (q - p).norm();
  if (len < 1e-6) return false;
  const Vector2d dir(std::cos(heading), std::sin(heading));
  const Vector2d mid = 0.5 * (p + q), line_along = (q - p) / len;
  const double min_cos_parallel = std::cos(20.0 * M_PI / 180.0);
  for (const EdgeFrame& e : edge_frames(outline)) {
    if (std::fabs(e.normal.dot(dir)) < 0.5) continue;   // the crossing goes along this side, not through it
    if (std::fabs(e.along.dot(line_along)) < min_cos_parallel) continue;
    if (std::fabs(e.normal.dot(mid - e.mid)) > tolerance) continue;
    if (std::fabs(e.along.dot(mid - e.mid)) >= 0.5 * e.length) continue;   // its middle beside the side
    return true;
  }
  return false;
}

Line lengthened(const Line& l, double by)
{
  const double len = (l.second - l.first).norm();
  if (len < 1e-6) return l;
  const Vector2d d = (l.second - l.first) / len * by;
  return {l.first - d, l.second + d};
}

std::vector<Line> clip_lines(const std::vector<Vector2d>& points, const std::vector<Vector2d>& origins, const SideReach& side_reach,
                             double line_extension)
{
  if (points.size() != 4) {
    std::vector<Line> lines = gateway_edges(points);
    for (auto& l : lines) l = lengthened(l, line_extension);
    return lines;
  }
  std::vector<Line> out;
  for (const EdgeFrame& e : edge_frames(points)) {
    const bool open = std::any_of(origins.begin(), origins.end(),
                                  [&](const Vector2d& o) { return e.just_beyond(o, side_reach.reach, side_reach.min_depth); });
    if (!open) out.push_back(e.line);
  }
  return out;
}

double widest_opening(const Line& side, const std::vector<rgmap::LineSegment>& walls, double tolerance)
{
  const Vector2d a = side.first;
  const double length = (side.second - a).norm();
  if (length < 1e-9) return 0.0;
  const Vector2d along = (side.second - a) / length, normal(-along.y(), along.x());
  const double min_cos = std::cos(15.0 * M_PI / 180.0);
  std::vector<std::pair<double, double>> covered;   // [t0, t1] along the side
  for (const auto& w : walls) {
    const Vector2d d = w.b - w.a;
    if (d.norm() < 1e-9 || std::fabs(d.normalized().dot(along)) < min_cos) continue;
    if (std::fabs(normal.dot(w.a - a)) > tolerance || std::fabs(normal.dot(w.b - a)) > tolerance) continue;
    double t0 = along.dot(w.a - a), t1 = along.dot(w.b - a);
    if (t0 > t1) std::swap(t0, t1);
    t0 = std::max(t0, 0.0);
    t1 = std::min(t1, length);
    if (t1 > t0) covered.push_back({t0, t1});
  }
  std::sort(covered.begin(), covered.end());
  double widest = 0.0, reached = 0.0;
  for (const auto& [t0, t1] : covered) {
    widest = std::max(widest, t0 - reached);
    reached = std::max(reached, t1);
  }
  return std::max(widest, length - reached);
}

bool OpeningTest::open(const EdgeFrame& side, const std::vector<rgmap::LineSegment>& walls) const
{
  return widest_opening(side.line, walls, tolerance) >= std::min(min_open, 0.8 * side.length);
}

std::vector<StemSide> stems_entered(const std::vector<Vector2d>& points, const std::vector<Vector2d>& origins, const SideReach& side_reach,
                                    const std::vector<rgmap::LineSegment>& walls, const OpeningTest& test, StemKind kind)
{
  std::vector<StemSide> out;
  if (points.size() != 4) return out;
  const std::vector<EdgeFrame> sides = edge_frames(points);
  if (sides.size() != 4) return out;
  for (size_t k = 0; k < 4; ++k) {
    const EdgeFrame& s = sides[k];
    if (std::none_of(origins.begin(), origins.end(),
                     [&](const Vector2d& o) { return s.just_beyond(o, side_reach.reach, side_reach.min_depth); }))
      continue;
    // The side opposite: for a T, a wall (not more hallway or a branch).
    if (kind == StemKind::kT && test.open(sides[(k + 2) % 4], walls)) continue;
    if (!test.open(sides[(k + 1) % 4], walls) || !test.open(sides[(k + 3) % 4], walls)) continue;   // a hallway past it
    out.push_back({s, std::max(sides[(k + 1) % 4].length, sides[(k + 3) % 4].length)});
  }
  return out;
}

}  // namespace rgnav::rg_kernel
