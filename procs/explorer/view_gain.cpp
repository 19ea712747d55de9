#include "explorer/view_gain.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "explorer/frontiers.h"
#include "geometry/segment2.h"

namespace rgnav::explorer {

using Eigen::Vector2d;

double unknown_area_beyond(const rgmap::RgMap& map, const Vector2d& from, const Vector2d& outward, const GainOptions& o)
{
  if (o.range_m <= 0.0 || outward.norm() < 1e-9) return 0.0;
  // The lines near enough to cut a ray, map frame (what lies free is frontiers.h's known_free).
  std::vector<std::pair<Vector2d, Vector2d>> lines;
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    for (const auto& s : r.segments) {
      const Vector2d a = r.map_from_region * s.a, b = r.map_from_region * s.b;
      if (geometry::point_segment_distance(from, a, b) <= o.range_m) lines.emplace_back(a, b);
    }
  }
  // Rays as far apart at the fan's rim as the samples along them: each sample stands for a patch
  // of about step x step there, and r * dtheta * step nearer in.
  const int rays = std::max(3, static_cast<int>(std::ceil(2.0 * o.fan_rad * o.range_m / o.step_m)) + 1);
  const double dtheta = 2.0 * o.fan_rad / (rays - 1);
  const double heading = std::atan2(outward.y(), outward.x());
  double area = 0.0;
  for (int k = 0; k < rays; ++k) {
    const double a = heading - o.fan_rad + k * dtheta;
    const Vector2d dir(std::cos(a), std::sin(a));
    double reach = o.range_m;
    for (const auto& [p, q] : lines) {
      const auto hit = geometry::ray_meets_line(from, dir, p, q, 1e-12);
      if (hit && hit->along_ray > 0.0 && hit->along_line >= 0.0 && hit->along_line <= 1.0)
        reach = std::min(reach, hit->along_ray);
    }
    for (double r = o.step_m; r <= reach; r += o.step_m)
      if (!known_free(map, from + r * dir)) area += r * dtheta * o.step_m;
  }
  return area;
}

}  // namespace rgnav::explorer
