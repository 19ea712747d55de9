#include "explorer/place_view.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::explorer {

using Eigen::Vector2d;

namespace {

// Length of segment a-b inside the disc of radius r around c.
double length_in_disc(const Vector2d& a, const Vector2d& b, const Vector2d& c, double r)
{
  const Vector2d d = b - a, f = a - c;
  const double aa = d.squaredNorm();
  if (aa < 1e-12) return 0.0;
  // |f + t d|^2 = r^2
  const double bb = 2 * f.dot(d), cc = f.squaredNorm() - r * r;
  const double disc = bb * bb - 4 * aa * cc;
  if (disc <= 0) return 0.0;
  const double s = std::sqrt(disc);
  const double t0 = std::max(0.0, (-bb - s) / (2 * aa)), t1 = std::min(1.0, (-bb + s) / (2 * aa));
  return t1 > t0 ? (t1 - t0) * std::sqrt(aa) : 0.0;
}

}  // namespace

PlaceView view_of_place(const rgmap::RgMap& map, const Vector2d& map_point, const PlaceViewOptions& o)
{
  PlaceView v;
  v.free_samples = 0;
  std::vector<std::pair<const rgmap::Region*, geometry::Pose2>> near;   // with region_from_map
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    const geometry::Pose2 region_from_map = r.map_from_region.inverse();
    const Vector2d p = region_from_map * map_point;
    if ((p.array() < r.bbox_min.array() - o.radius_m).any() || (p.array() > r.bbox_max.array() + o.radius_m).any())
      continue;
    near.emplace_back(&r, region_from_map);
    for (const auto& s : r.segments) v.wall_m += length_in_disc(s.a, s.b, p, o.radius_m);
  }
  const int n = static_cast<int>(std::floor(o.radius_m / o.sample_m));
  for (int iy = -n; iy <= n; ++iy)
    for (int ix = -n; ix <= n; ++ix) {
      const Vector2d off(ix * o.sample_m, iy * o.sample_m);
      if (off.squaredNorm() > o.radius_m * o.radius_m) continue;
      const Vector2d q = map_point + off;
      for (const auto& [r, region_from_map] : near)
        if (r->freespace.is_free(region_from_map * q)) {
          ++v.free_samples;
          break;
        }
    }
  return v;
}

bool place_changed(const PlaceView& then, const PlaceView& now, const PlaceViewOptions& o)
{
  if (!then.known() || !now.known()) return false;
  const double sample_area = o.sample_m * o.sample_m;
  return std::abs(now.free_samples - then.free_samples) * sample_area >= o.changed_area_m2 ||
         std::fabs(now.wall_m - then.wall_m) >= o.changed_wall_m;
}

nlohmann::json place_view_json(const PlaceView& v) { return {v.free_samples, v.wall_m}; }

PlaceView place_view_from_json(const nlohmann::json& j)
{
  if (!j.is_array() || j.size() != 2) throw std::invalid_argument("a place view is not [free_samples, wall_m]");
  PlaceView v;
  v.free_samples = j[0].get<int>();
  v.wall_m = j[1].get<double>();
  if (v.free_samples < -1 || !std::isfinite(v.wall_m) || v.wall_m < 0)
    throw std::invalid_argument("a place view is out of range");
  return v;
}

}  // namespace rgnav::explorer
