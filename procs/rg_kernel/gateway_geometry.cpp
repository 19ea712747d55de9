#include "procs/rg_kernel/gateway_geometry.h"

#include <cmath>

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

// [m] an origin this far beside the ends of a side still counts as beyond it (a robot leaving a
// junction diagonally, pose noise).
constexpr double kSideMargin = 0.5;

}  // namespace

std::vector<Line> gateway_edges(const std::vector<Vector2d>& points)
{
  std::vector<Line> edges;
  if (points.size() == 4) {
    for (size_t k = 0; k < 4; ++k) edges.push_back({points[k], points[(k + 1) % 4]});
    return edges;
  }
  for (size_t k = 0; k + 1 < points.size(); k += 2) edges.push_back({points[k], points[k + 1]});
  return edges;
}

std::vector<Line> clip_lines(const std::vector<Vector2d>& points, const std::vector<Vector2d>& origins, double side_reach)
{
  std::vector<Line> edges = gateway_edges(points);
  if (points.size() != 4) return edges;
  const Vector2d centre = 0.25 * (points[0] + points[1] + points[2] + points[3]);
  std::vector<Line> out;
  for (const auto& [a, b] : edges) {
    Vector2d u = b - a;
    const double len = u.norm();
    if (len < 1e-6) continue;
    u /= len;
    Vector2d n(-u.y(), u.x());
    const Vector2d m = 0.5 * (a + b);
    if (n.dot(centre - m) > 0) n = -n;   // outward
    bool open = false;
    for (const auto& o : origins) {
      const double depth = n.dot(o - m), along = u.dot(o - m);
      if (depth > 0 && depth < side_reach && std::fabs(along) < 0.5 * len + kSideMargin) {
        open = true;
        break;
      }
    }
    if (!open) out.push_back({a, b});
  }
  return out;
}

}  // namespace rgnav::rg_kernel
