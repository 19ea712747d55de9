#include "localizer/path_search.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>

namespace rgnav::localizer {

namespace {

// The views' points in the current base frame, in an order that mixes views and directions:
// the first few points of a candidate already say whether it can be among the best.
std::vector<Eigen::Vector2d> path_points(const std::vector<PlacedView>& views, const PathSearchOptions& options)
{
  std::vector<Eigen::Vector2d> pts;
  const size_t want = static_cast<size_t>(std::max(1, options.views));
  for (size_t i : spread_indices(views.size(), std::min(views.size(), want)))
    for (const auto& p : coarse_points(*views[i].points, options.beams_per_view)) pts.push_back(views[i].now_from_then * p);
  std::mt19937 rng(1);   // fixed: the same views give the same search
  std::shuffle(pts.begin(), pts.end(), rng);
  return pts;
}

}  // namespace

std::vector<Hypothesis> path_search(const RegionMaps& maps, const std::vector<PlacedView>& views, const BeamScorer& scorer,
                                    const PathSearchOptions& options,
                                    const std::function<bool(const Hypothesis&, const Hypothesis&)>& distinct,
                                    const std::function<void()>& progress)
{
  const auto pts = path_points(views, options);
  if (pts.empty()) return {};
  const int nh = std::max(1, options.headings);
  const auto rotated = rotated_per_heading(pts, nh);
  // The best `pool` candidates so far (one per cell), worst on top.
  const auto worse = [](const Hypothesis& a, const Hypothesis& b) { return a.score > b.score; };
  std::priority_queue<Hypothesis, std::vector<Hypothesis>, decltype(worse)> pool(worse);
  const size_t pool_size = static_cast<size_t>(std::max(options.pool, options.keep));
  constexpr size_t kCheckEvery = 8;   // points between bound checks
  for (const auto& [id, region] : maps.regions()) {
    if (region->field.empty()) continue;
    for (const auto& pos : region->free_positions) {
      const double admit = pool.size() < pool_size ? -1e300 : pool.top().score;
      double cell_best = admit;
      int cell_h = -1;
      for (int h = 0; h < nh; ++h) {
        const auto& rp = rotated[static_cast<size_t>(h)];
        double s = 0;
        size_t k = 0;
        for (; k < rp.size(); ++k) {
          s += scorer.log_p(region->field.distance(pos + rp[k]));
          if ((k + 1) % kCheckEvery == 0 && s <= cell_best) break;   // cannot beat what it must: log p <= 0
        }
        if (k == rp.size() && s > cell_best) {
          cell_best = s;
          cell_h = h;
        }
      }
      if (cell_h < 0) continue;
      pool.push({id, geometry::Pose2(pos, 2 * M_PI * cell_h / nh), cell_best});
      if (pool.size() > pool_size) pool.pop();
    }
    if (progress) progress();
  }
  std::vector<Hypothesis> ranked;
  ranked.reserve(pool.size());
  for (; !pool.empty(); pool.pop()) ranked.push_back(pool.top());
  std::reverse(ranked.begin(), ranked.end());   // best first
  std::vector<Hypothesis> out;
  for (const auto& h : ranked) {
    if (static_cast<int>(out.size()) >= options.keep) break;
    if (std::all_of(out.begin(), out.end(), [&](const Hypothesis& o) { return distinct(o, h); })) out.push_back(h);
  }
  return out;
}

}  // namespace rgnav::localizer
