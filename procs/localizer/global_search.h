// Global localization by recognising the region and the place in it (beyond TumBot, which had
// none; diss. 5.3): the scan is matched exhaustively against every region's line map at
// candidate poses — freespace cells (so only plausible places, diss. 5.2) times headings — and
// the best candidate per place is kept. Particles are then seeded around the best candidates
// (also used for sensor resetting when the filter loses track).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/pose2.h"
#include "localizer/localizer_options.h"
#include "localizer/path_score.h"
#include "localizer/region_maps.h"
#include "localizer/scan_model.h"

namespace rgnav::localizer {

struct Hypothesis
{
  int64_t region = 0;
  geometry::Pose2 region_from_base;
  double score = 0;   // sum of log p over the beams used
};

// Up to `beams` of the points, evenly spread: the coarse search's share of a scan.
std::vector<Eigen::Vector2d> coarse_points(const std::vector<Eigen::Vector2d>& points, int beams);
// The points turned once per heading: [h] holds them turned by 2 pi h / headings (a search
// scores every place at every heading with these, instead of turning the points each time).
std::vector<std::vector<Eigen::Vector2d>> rotated_per_heading(const std::vector<Eigen::Vector2d>& points, int headings);
// Up to `m` indices spread evenly over 0 .. n-1, ascending and distinct: the first and the last
// among them (only the last for m = 1). Views spread over a path keep its shape.
std::vector<size_t> spread_indices(size_t n, size_t m);

// A candidate moved to the best pose of a small local grid around it (hill climbing in steps
// of step_xy / step_theta, halved until below a tenth), rescored with `scorer`.
Hypothesis refine(const RegionModel& region, Hypothesis h, const std::vector<Eigen::Vector2d>& base_points,
                  const BeamScorer& scorer, double step_xy, double step_theta);
// The same with any score of a pose in h's region (e.g. path_score.h).
Hypothesis refine(Hypothesis h, const std::function<double(const geometry::Pose2&)>& score, double step_xy, double step_theta);

// The best `options.hypotheses` candidates, best first. With `path_points` (the views of the
// path, view_path.h, each scored in the region holding its place, path_score.h) every place keeps the heading the scan fits best
// there; half the kept places are the scan's best, half those that best explain the whole
// path: a hallway view fits every hallway of a building, the path along it far fewer places,
// and the true one must not fall out of the kept candidates among look-alikes. Scores are then
// the path's, best first.
std::vector<Hypothesis> global_search(const RegionMaps& maps, const std::vector<Eigen::Vector2d>& base_points,
                                      const GlobalOptions& options, const ScanModel& scan,
                                      const std::vector<PlacedView>& path = {}, double bbox_margin = 0.3);

}  // namespace rgnav::localizer
