#include "sim_operator.h"

#include <cmath>
#include <limits>

namespace rgnav::demo {

namespace {

double distance_to_segment(const sim::Vec2& p, const sim::Vec2& a, const sim::Vec2& b)
{
  const sim::Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

double distance_to_polygon(const sim::Vec2& p, const std::vector<sim::Vec2>& poly)
{
  if (sim::point_in_polygon(p, poly)) return 0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) best = std::min(best, distance_to_segment(p, poly[i], poly[(i + 1) % poly.size()]));
  return best;
}

}  // namespace

sim::Vec2 SimOperator::to_world(double map_x, double map_y) const
{
  const auto& s = world_.start;
  const double c = std::cos(s.theta), n = std::sin(s.theta);
  return {s.x + c * map_x - n * map_y, s.y + n * map_x + c * map_y};
}

Answer SimOperator::name(int64_t region_id, double map_x, double map_y)
{
  const auto known = answers_.find(region_id);
  if (known != answers_.end()) return known->second;
  const sim::Vec2 w = to_world(map_x, map_y);
  const sim::Region* best = nullptr;
  double best_d = reach_;
  for (const auto& r : world_.regions) {
    const double d = distance_to_polygon(w, r.polygon);
    if (d <= best_d) {
      best_d = d;
      best = &r;
      if (d == 0) break;
    }
  }
  Answer a;
  a.world_x = w.x();
  a.world_y = w.y();
  std::string base;
  if (best) {
    a.room = best->name;
    a.kind = sim::to_string(best->kind);
    base = best->name;
  } else {
    base = "area_" + std::to_string(region_id);
  }
  // One name per region: a room the RG map cut in two gives "office_w1" and "office_w1_2".
  a.name = base;
  for (int k = 2;; ++k) {
    bool taken = false;
    for (const auto& [id, other] : answers_) taken = taken || other.name == a.name;
    if (!taken) break;
    a.name = base + "_" + std::to_string(k);
  }
  answers_[region_id] = a;
  return a;
}

}  // namespace rgnav::demo
