#include "truth_frames.h"

#include <cmath>

#include "rgmap_metrics.h"

namespace rgnav::localize_eval {

using Eigen::Vector2d;
using geometry::Pose2;

Pose2 TruthFrames::in_region(int64_t region, const Pose2& world_from_base) const
{
  const auto it = world_from_region.find(region);
  return it == world_from_region.end() ? Pose2() : it->second.inverse() * world_from_base;
}

int64_t TruthFrames::region_at(const Pose2& world_from_base, int64_t prefer) const
{
  const auto holds = [&](int64_t id) {
    const auto* r = map->region(id);
    return r && world_from_region.count(id) && r->freespace.is_free(in_region(id, world_from_base).translation());
  };
  if (prefer != 0 && holds(prefer)) return prefer;
  for (const auto& [id, pose] : world_from_region)
    if (holds(id)) return id;
  return 0;
}

constexpr double kMatch = 0.05;   // [m]

TruthFrames fit_truth_frames(const rgmap_pipeline::OfflineRun& run, const std::vector<Pose2>& truth_at_node,
                             const Pose2& base_from_laser)
{
  TruthFrames f;
  f.map = &run.map;
  std::vector<Vector2d> est, tru;
  for (size_t k = 0; k < run.nodes.size() && k < truth_at_node.size(); ++k) {
    est.push_back((run.nodes[k].map_from_base * base_from_laser).translation());
    tru.push_back((truth_at_node[k] * base_from_laser).translation());
  }
  f.world_from_map = rgmap_pipeline::fit_rigid(est, tru);
  for (const auto& [id, positions] : run.robot_positions) {
    const auto* region = run.map.region(id);
    if (!region) continue;
    const Pose2 region_from_map = region->map_from_region.inverse();
    std::vector<Vector2d> a, b;
    for (const auto& p : positions) {
      // The region holds its scans' laser positions as they were when stacked; the nodes hold
      // the final estimates. The nearest node is that scan's (scans are >= 10 cm apart, later
      // corrections inside a region a few cm).
      size_t best = est.size();
      double best_d2 = kMatch * kMatch;
      for (size_t k = 0; k < est.size(); ++k)
        if ((est[k] - p).squaredNorm() < best_d2) {
          best_d2 = (est[k] - p).squaredNorm();
          best = k;
        }
      if (best == est.size()) continue;
      a.push_back(region_from_map * p);
      b.push_back(tru[best]);
    }
    Vector2d lo = Vector2d::Constant(1e300), hi = Vector2d::Constant(-1e300);
    for (const auto& p : a) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const bool enough = a.size() >= 3 && (hi - lo).norm() >= 0.5;
    const Pose2 w = enough ? rgmap_pipeline::fit_rigid(a, b) : f.world_from_map * region->map_from_region;
    // Fitted on laser positions: the same rigid transform holds for base poses.
    f.world_from_region[id] = w;
    double se = 0;
    for (size_t k = 0; k < a.size(); ++k) se += (w * a[k] - b[k]).squaredNorm();
    f.fit_rmse[id] = a.empty() ? 0.0 : std::sqrt(se / static_cast<double>(a.size()));
    f.fit_points[id] = enough ? static_cast<int>(a.size()) : 0;
  }
  return f;
}

}  // namespace rgnav::localize_eval
