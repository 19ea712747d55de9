#include "localizer/global_search.h"

#include <algorithm>
#include <cmath>

namespace rgnav::localizer {

std::vector<Eigen::Vector2d> coarse_points(const std::vector<Eigen::Vector2d>& points, int beams)
{
  std::vector<Eigen::Vector2d> pts;
  const double step = std::max(1.0, static_cast<double>(points.size()) / std::max(1, beams));
  for (double k = 0; k < static_cast<double>(points.size()); k += step) pts.push_back(points[static_cast<size_t>(k)]);
  return pts;
}

std::vector<std::vector<Eigen::Vector2d>> rotated_per_heading(const std::vector<Eigen::Vector2d>& points, int headings)
{
  const int nh = std::max(1, headings);
  std::vector<std::vector<Eigen::Vector2d>> rotated(static_cast<size_t>(nh));
  for (int h = 0; h < nh; ++h) {
    const Eigen::Matrix2d r = geometry::Pose2(0, 0, 2 * M_PI * h / nh).rotation();
    for (const auto& p : points) rotated[static_cast<size_t>(h)].push_back(r * p);
  }
  return rotated;
}

std::vector<size_t> spread_indices(size_t n, size_t m)
{
  std::vector<size_t> picked;
  if (n == 0 || m == 0) return picked;
  for (size_t k = 0; k < m; ++k) {
    const size_t i = m == 1 ? n - 1 : k * (n - 1) / (m - 1);
    if (picked.empty() || picked.back() != i) picked.push_back(i);
  }
  return picked;
}

Hypothesis refine(const RegionModel& region, Hypothesis h, const std::vector<Eigen::Vector2d>& base_points,
                  const BeamScorer& scorer, double step_xy, double step_theta)
{
  return refine(h, [&](const geometry::Pose2& p) { return scorer.score(region.field, p, base_points); }, step_xy, step_theta);
}

Hypothesis refine(Hypothesis h, const std::function<double(const geometry::Pose2&)>& score, double step_xy, double step_theta)
{
  h.score = score(h.region_from_base);
  for (double sxy = step_xy, sth = step_theta; sxy > 0.1 * step_xy; sxy *= 0.5, sth *= 0.5) {
    bool moved = true;
    for (int guard = 0; moved && guard < 20; ++guard) {
      moved = false;
      const geometry::Pose2 c = h.region_from_base;
      for (const auto& d : {Eigen::Vector3d(sxy, 0, 0), Eigen::Vector3d(-sxy, 0, 0), Eigen::Vector3d(0, sxy, 0),
                            Eigen::Vector3d(0, -sxy, 0), Eigen::Vector3d(0, 0, sth), Eigen::Vector3d(0, 0, -sth)}) {
        const geometry::Pose2 p(c.x() + d.x(), c.y() + d.y(), c.theta() + d.z());
        const double sc = score(p);
        if (sc > h.score) {
          h.score = sc;
          h.region_from_base = p;
          moved = true;
        }
      }
    }
  }
  return h;
}

std::vector<Hypothesis> global_search(const RegionMaps& maps, const std::vector<Eigen::Vector2d>& base_points,
                                      const GlobalOptions& options, const ScanModel& scan,
                                      const std::vector<PlacedView>& path, double bbox_margin)
{
  std::vector<Hypothesis> found;
  if (base_points.empty()) return found;
  // A coarse grid of candidates needs a broad hit noise to see the true place at all.
  const BeamScorer scorer(options.sigma, scan.z_hit, scan.z_rand, scan.max_distance);
  const auto pts = coarse_points(base_points, options.beams);
  const int nh = std::max(1, options.headings);
  const auto rotated = rotated_per_heading(pts, nh);
  for (const auto& [id, region] : maps.regions()) {
    if (region->field.empty()) continue;
    for (const auto& pos : region->free_positions) {
      double best = -1e300;
      int best_h = 0;
      for (int h = 0; h < nh; ++h) {
        double s = 0;
        for (const auto& p : rotated[static_cast<size_t>(h)]) s += scorer.log_p(region->field.distance(pos + p));
        if (s > best) {
          best = s;
          best_h = h;
        }
      }
      found.push_back({id, geometry::Pose2(pos, 2 * M_PI * best_h / nh), best});
    }
  }
  const size_t keep = std::min(found.size(), static_cast<size_t>(std::max(1, options.hypotheses)));
  const auto best_first = [](const Hypothesis& a, const Hypothesis& b) { return a.score > b.score; };
  if (path.size() < 2) {
    std::partial_sort(found.begin(), found.begin() + static_cast<long>(keep), found.end(), best_first);
    found.resize(keep);
    return found;
  }
  // Half the kept places are the scan's best, half the path's best (a candidate on the coarse
  // grid may miss the true pose by half a cell and half a heading step, which the far end of a
  // path of several metres feels far more than one scan does: the true place must not drop out
  // of both rankings at once).
  const size_t by_scan = keep / 2;
  std::partial_sort(found.begin(), found.begin() + static_cast<long>(by_scan), found.end(), best_first);
  // A few views spread over the path (its oldest and the current one among them): the ranking
  // needs the path's shape, not every view.
  constexpr size_t kPathViews = 4;
  std::vector<PlacedView> few;
  for (const size_t i : spread_indices(path.size(), kPathViews)) few.push_back(path[i]);
  for (auto& h : found) h.score = path_score(maps, scorer, h.region, h.region_from_base, few, bbox_margin);
  std::partial_sort(found.begin() + static_cast<long>(by_scan), found.begin() + static_cast<long>(keep), found.end(), best_first);
  found.resize(keep);
  std::sort(found.begin(), found.end(), best_first);   // by the path
  return found;
}

}  // namespace rgnav::localizer
