#include "explorer/opening.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/segment2.h"

namespace rgnav::explorer {

using Eigen::Vector2d;

std::optional<Vector2d> aim_through_opening(const rgmap::RgMap& map, const Vector2d& crossing, double heading,
                                            double depth, double width, const OpeningOptions& o)
{
  if (o.search_m <= 0.0 || o.step_m <= 0.0) return crossing;
  const Vector2d along(std::cos(heading), std::sin(heading));
  const Vector2d across(-along.y(), along.x());
  const double length = o.back_m + depth;
  // The lines near enough to cross a lane (map frame).
  const double reach = o.search_m + 0.5 * width + length;
  std::vector<std::pair<Vector2d, Vector2d>> lines;
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    for (const auto& s : r.segments) {
      const Vector2d a = r.map_from_region * s.a, b = r.map_from_region * s.b;
      if (geometry::point_segment_distance(crossing, a, b) <= reach) lines.emplace_back(a, b);
    }
  }
  // Lane k runs at offset (k - n) * step across the crossing, from back_m before it to depth
  // past it; `hit` is how far along it the first line lies (infinity: none).
  const int n = static_cast<int>(std::floor(o.search_m / o.step_m));
  constexpr double kNone = std::numeric_limits<double>::infinity();
  std::vector<double> hit(static_cast<size_t>(2 * n + 1), kNone);
  for (int k = 0; k <= 2 * n; ++k) {
    const Vector2d from = crossing + (k - n) * o.step_m * across - o.back_m * along;
    for (const auto& [a, b] : lines) {
      const auto m = geometry::ray_meets_line(from, along, a, b, 1e-9);
      if (m && m->along_ray > 0.0 && m->along_ray < length && m->along_line >= 0.0 && m->along_line <= 1.0)
        hit[static_cast<size_t>(k)] = std::min(hit[static_cast<size_t>(k)], m->along_ray);
    }
  }
  std::vector<double> hits;
  for (const double h : hit)
    if (h < kNone) hits.push_back(h);
  if (hits.empty()) return crossing;   // nothing known to aim by
  // The wall the gateway is in: where the first quarter of the lanes that meet a line meet it
  // (a chair or a person in front of it meets only a few). A lane through the opening reaches
  // wall_pass_m past the wall's line before it meets anything (furniture in the room beyond
  // is no wall across the opening).
  std::nth_element(hits.begin(), hits.begin() + static_cast<std::ptrdiff_t>(hits.size() / 4), hits.end());
  const double wall = hits[hits.size() / 4];
  const auto lane_free = [&](int k) {
    // Lanes past the search range are not looked at and count as free.
    return k < 0 || k > 2 * n || hit[static_cast<size_t>(k)] >= std::min(wall + o.wall_pass_m, length);
  };
  const int half = static_cast<int>(std::ceil(0.5 * width / o.step_m));
  const auto room_at = [&](int k) {
    for (int j = k - half; j <= k + half; ++j)
      if (!lane_free(j)) return false;
    return true;
  };
  // The nearest offset with room for the robot, the crossing's own first.
  for (int d = 0; d <= n; ++d)
    for (const int k : {n - d, n + d})
      if (room_at(k)) return Vector2d(crossing + (k - n) * o.step_m * across);
  return std::nullopt;
}

}  // namespace rgnav::explorer
