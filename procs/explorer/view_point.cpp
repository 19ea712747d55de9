#include "explorer/view_point.h"

#include <algorithm>
#include <cmath>

namespace rgnav::explorer {

using Eigen::Vector2d;

std::optional<ViewPoint> view_point(const planner::RegionPlanner& region, const std::vector<int32_t>& pieces,
                                    const Vector2d& target, const Vector2d& outward, double wanted_clearance,
                                    const ViewOptions& options)
{
  const planner::RegionGrid& grid = region.grid();
  struct Candidate
  {
    double score;
    Vector2d point;
  };
  std::vector<Candidate> candidates;
  const planner::Cell centre = grid.cell_of(target);
  const int span = static_cast<int>(std::ceil(options.range_m / grid.resolution()));
  for (int dy = -span; dy <= span; ++dy)
    for (int dx = -span; dx <= span; ++dx) {
      const planner::Cell c(centre.x() + dx, centre.y() + dy);
      if (!grid.free(c) || std::find(pieces.begin(), pieces.end(), grid.component(c)) == pieces.end()) continue;
      const Vector2d p = grid.center_of(c);
      const double d = (p - target).norm();
      if (d > options.range_m) continue;
      const double shortfall = std::max(0.0, wanted_clearance - static_cast<double>(grid.clearance(c)));
      candidates.push_back({d + options.clearance_weight * shortfall, p});
    }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  // The nearest with a clear line of sight (tested in order: most candidates are never looked at).
  for (const Candidate& c : candidates) {
    if (region.crosses_line(c.point, target)) continue;
    const Vector2d to = target - c.point;
    const Vector2d dir = to.norm() > grid.resolution() ? to : outward;
    return ViewPoint{c.point, std::atan2(dir.y(), dir.x())};
  }
  return std::nullopt;
}

}  // namespace rgnav::explorer
