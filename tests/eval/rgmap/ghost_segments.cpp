#include "ghost_segments.h"

#include <algorithm>
#include <cmath>

namespace rgnav::rgmap_pipeline {

using Eigen::Vector2d;

StaticSurfaces::StaticSurfaces(const sim::World& world, double scan_height)
    : scene_(world), doors_closed_(world.doors.size(), 0), scan_height_(scan_height)
{
}

double StaticSurfaces::share_away(const Vector2d& a, const Vector2d& b, double tolerance) const
{
  constexpr double kStep = 0.02;  // [m]
  const int n = std::max(2, static_cast<int>(std::ceil((b - a).norm() / kStep)) + 1);
  const sim::HeightBand band{scan_height_, scan_height_};
  int away = 0;
  for (int k = 0; k < n; ++k) {
    const Vector2d p = a + (b - a) * (static_cast<double>(k) / (n - 1));
    // clearance() reports anything beyond its search radius as infinitely far.
    if (!(scene_.clearance(p, tolerance, band, doors_closed_).distance <= tolerance)) ++away;
  }
  return static_cast<double>(away) / n;
}

GhostSegments count_ghost_segments(const rgmap::RgMap& map, const geometry::Pose2& world_from_map,
                                   const StaticSurfaces& statics, double tolerance)
{
  GhostSegments out;
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    const geometry::Pose2 world_from_region = world_from_map * r.map_from_region;
    for (const auto& s : r.segments) {
      ++out.segments;
      const Vector2d a = world_from_region * s.a, b = world_from_region * s.b;
      if (statics.share_away(a, b, tolerance) <= 0.5) continue;
      ++out.ghosts;
      out.ghost_length_m += (b - a).norm();
      out.ghost_list.emplace_back(a, b);
    }
  }
  return out;
}

}  // namespace rgnav::rgmap_pipeline
