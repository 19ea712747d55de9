#include "procs/rg_kernel/narrowing.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "procs/rg_kernel/gateway_geometry.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

// [m] Probes start past the wall's thickness and the door's jambs, in steps finer than a door.
constexpr double kProbeFrom = 0.4;
constexpr double kProbeStep = 0.2;
// [m] A probe stays this far short of the wall the way runs into (scan noise on its segment).
constexpr double kProbeMargin = 0.1;

// Distance from `origin` along `dir` (unit) to the nearest wall segment, at most `cap`.
double free_run(const Vector2d& origin, const Vector2d& dir, const std::vector<rgmap::LineSegment>& walls, double cap)
{
  double best = cap;
  for (const auto& w : walls) {
    const auto hit = ray_meets_line(origin, dir, w.a, w.b);
    if (hit && hit->along_ray > 1e-6 && hit->along_ray < best && hit->along_line >= 0 && hit->along_line <= 1)
      best = hit->along_ray;
  }
  return best;
}

// The median width across `along` at probes from the line's middle `mid` into direction `into`.
double side_width(const Vector2d& mid, const Vector2d& into, const Vector2d& along, const std::vector<rgmap::LineSegment>& walls,
                  const NarrowingOptions& o)
{
  const double depth = free_run(mid, into, walls, o.cap) - kProbeMargin;
  std::vector<double> widths;
  for (double t = kProbeFrom; t <= std::min(o.probe_depth, depth) + 1e-9; t += kProbeStep) {
    const Vector2d x = mid + t * into;
    widths.push_back(free_run(x, along, walls, o.cap) + free_run(x, -along, walls, o.cap));
  }
  if (widths.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(widths.begin(), widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 2), widths.end());
  return widths[widths.size() / 2];
}

}  // namespace

NarrowingProfile narrowing_profile(const Vector2d& p, const Vector2d& q, const Vector2d& heading,
                                   const std::vector<rgmap::LineSegment>& walls, const NarrowingOptions& o)
{
  NarrowingProfile out;
  out.width = (q - p).norm();
  if (out.width < 1e-6) return out;
  const Vector2d along = (q - p) / out.width, mid = 0.5 * (p + q);
  Vector2d normal(-along.y(), along.x());
  if (normal.dot(heading) < 0) normal = -normal;   // the side the crossing went to
  out.before = side_width(mid, -normal, along, walls, o);
  out.after = side_width(mid, normal, along, walls, o);
  // A side with no room for a probe (the way runs into a wall at once) says nothing against it.
  auto wide_enough = [&](double side) { return std::isnan(side) || out.width <= o.max_width_ratio * side; };
  out.narrowing = o.max_width_ratio <= 0 || (wide_enough(out.before) && wide_enough(out.after));
  return out;
}

}  // namespace rgnav::rg_kernel
