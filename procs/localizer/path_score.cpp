#include "localizer/path_score.h"

#include <deque>
#include <set>

namespace rgnav::localizer {

using geometry::Pose2;

std::pair<const RegionModel*, Pose2> holding_region(const RegionMaps& maps, int64_t region, const Pose2& region_from_base,
                                                    double bbox_margin, int hops)
{
  const RegionModel* start = maps.region(region);
  if (!start) return {nullptr, region_from_base};
  const auto holds = [&](const RegionModel& m, const Pose2& p) {
    return m.is_free(p.translation()) && m.in_bbox(p.translation(), bbox_margin);
  };
  if (holds(*start, region_from_base)) return {start, region_from_base};
  // Breadth first through the gateways: the nearest region (fewest gateways) that holds it.
  struct Step { const RegionModel* m; Pose2 pose; int depth; };
  std::deque<Step> queue{{start, region_from_base, 0}};
  std::set<int64_t> seen{start->id};
  while (!queue.empty()) {
    const Step s = queue.front();
    queue.pop_front();
    if (s.depth >= hops) continue;
    for (const auto& link : s.m->links) {
      const RegionModel* n = maps.region(link.to);
      if (!n || !seen.insert(n->id).second) continue;
      const Pose2 there = link.here_from_there.inverse() * s.pose;
      if (holds(*n, there)) return {n, there};
      queue.push_back({n, there, s.depth + 1});
    }
  }
  return {start, region_from_base};
}

double path_score(const RegionMaps& maps, const BeamScorer& scorer, int64_t region, const Pose2& region_from_base,
                  const std::vector<PlacedView>& views, double bbox_margin)
{
  double s = 0;
  for (const auto& v : views) {
    const auto [m, pose] = holding_region(maps, region, region_from_base * v.now_from_then, bbox_margin);
    if (!m) return -1e300;
    s += scorer.score(m->field, pose, *v.points);
  }
  return s;
}

}  // namespace rgnav::localizer
