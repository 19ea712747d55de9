#include "wall_world.h"

#include <algorithm>
#include <limits>

#include "geometry/segment2.h"

namespace rgnav::testing {

Walls box(double x0, double y0, double x1, double y1)
{
  using V = Eigen::Vector2d;
  return {{V(x0, y0), V(x1, y0)}, {V(x1, y0), V(x1, y1)}, {V(x1, y1), V(x0, y1)}, {V(x0, y1), V(x0, y0)}};
}

void add(Walls* walls, const Walls& more) { walls->insert(walls->end(), more.begin(), more.end()); }

double nearest_wall(const Walls& walls, const Eigen::Vector2d& o, const Eigen::Vector2d& d, double min_t)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : walls) {
    const auto hit = geometry::ray_meets_line(o, d, w.a, w.b, 1e-12);
    if (hit && hit->along_ray > min_t && hit->along_line >= 0 && hit->along_line <= 1) best = std::min(best, hit->along_ray);
  }
  return best;
}

}  // namespace rgnav::testing
