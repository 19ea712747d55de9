#include "geometry/segment2.h"
#include "procs/rg_kernel/known_place.h"

#include <algorithm>
#include <cmath>

#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/region_builder.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;
using rgmap::Region;

KnownPlaces::KnownPlaces(const rgmap::RgMap& map, const std::map<int64_t, RegionBuilder>& builders, int64_t except,
                         KnownPlaceOptions options, const std::vector<Vector2d>& crossed)
    : options_(options)
{
  if (crossed.size() >= 2)
    for (const auto& line : gateway_edges(crossed)) gateway_lines_.push_back(line);
  for (const auto& [id, r] : map.regions()) {
    if (id == except || r.state != Region::State::kFinalised) continue;
    auto b = builders.find(id);
    if (b == builders.end()) continue;
    Place p;
    p.id = id;
    p.region = &r;
    for (const auto& o : b->second.laser_origins()) p.origins.push_back(r.map_from_region * o);
    places_.push_back(std::move(p));
  }
  for (const auto& [id, g] : map.gateways()) {
    if (g.neutralized || g.gateway_points.size() < 2) continue;
    const Region* a = map.region(g.region_a);
    if (!a) continue;
    // Every side of a crossing's outline: a line of sight out of the junction has left the region.
    for (const auto& [p, q] : gateway_edges(g.gateway_points))
      gateway_lines_.push_back({a->map_from_region * p, a->map_from_region * q});
  }
}

bool KnownPlaces::sees(const Place& q, const Vector2d& from, const Vector2d& to) const
{
  for (const auto& [a, b] : gateway_lines_)
    if (geometry::segments_cross(from, to, a, b)) return false;
  // Every cell on the way free in q's own bitmap: sample at half a cell.
  const geometry::Pose2 region_from_map = q.region->map_from_region.inverse();
  const double len = (to - from).norm();
  const double step = 0.5 * q.region->freespace.resolution();
  const int n = static_cast<int>(std::ceil(len / step));
  for (int i = 0; i <= n; ++i) {
    const Vector2d p = n == 0 ? to : from + (to - from) * (static_cast<double>(i) / n);
    if (!q.region->freespace.is_free(region_from_map * p)) return false;
  }
  return true;
}

int64_t KnownPlaces::region_holding(const Vector2d& p) const
{
  const double r2 = options_.max_origin_distance * options_.max_origin_distance;
  for (const Place& q : places_) {
    if (!q.region->freespace.is_free(q.region->map_from_region.inverse() * p)) continue;
    std::vector<std::pair<double, size_t>> near;
    for (size_t i = 0; i < q.origins.size(); ++i) {
      const double d2 = (q.origins[i] - p).squaredNorm();
      if (d2 <= r2) near.push_back({d2, i});
    }
    const size_t tried = std::min(near.size(), static_cast<size_t>(std::max(1, options_.max_lines_tried)));
    std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(tried), near.end());
    for (size_t k = 0; k < tried; ++k)
      if (sees(q, q.origins[near[k].second], p)) return q.id;
  }
  return 0;
}

}  // namespace rgnav::rg_kernel
