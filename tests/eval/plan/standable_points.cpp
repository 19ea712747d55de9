#include "standable_points.h"

namespace rgnav::plan_eval {

StandableSampler::StandableSampler(planner::GlobalPlanner& planner) : planner_(planner)
{
  for (const auto& [id, r] : planner_.map().regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    std::vector<std::pair<int, int>> cells;
    for (int y = 0; y < r.freespace.height(); ++y)
      for (int x = 0; x < r.freespace.width(); ++x)
        if (r.freespace.free(x, y)) cells.emplace_back(x, y);
    if (cells.empty()) continue;
    regions_.push_back(id);
    free_cells_[id] = std::move(cells);
  }
}

std::optional<RegionPoint> StandableSampler::sample_in(int64_t region, std::mt19937_64& rng, int tries)
{
  const auto it = free_cells_.find(region);
  const auto* rp = planner_.region_planner(region);
  const auto* r = planner_.map().region(region);
  if (it == free_cells_.end() || !rp || !r) return std::nullopt;
  std::uniform_int_distribution<size_t> pick(0, it->second.size() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double res = r->freespace.resolution();
  for (int k = 0; k < tries; ++k) {
    const auto [cx, cy] = it->second[pick(rng)];
    const Eigen::Vector2d p = r->freespace.region_from_grid() * Eigen::Vector2d((cx + unit(rng)) * res, (cy + unit(rng)) * res);
    if (rp->standable(p)) return RegionPoint{region, p};
  }
  return std::nullopt;
}

std::optional<RegionPoint> StandableSampler::sample(std::mt19937_64& rng, int tries)
{
  if (regions_.empty()) return std::nullopt;
  std::uniform_int_distribution<size_t> pick(0, regions_.size() - 1);
  for (int k = 0; k < tries; ++k)
    if (auto p = sample_in(regions_[pick(rng)], rng, 20)) return p;
  return std::nullopt;
}

Eigen::Vector2d in_map(const rgmap::RgMap& map, const RegionPoint& p)
{
  const auto* r = map.region(p.region);
  return r ? r->map_from_region * p.point : p.point;
}

}  // namespace rgnav::plan_eval
