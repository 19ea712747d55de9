// Global localization by recognising the region and the place in it (beyond TumBot, which had
// none; diss. 5.3): the scan is matched exhaustively against every region's line map at
// candidate poses — freespace cells (so only plausible places, diss. 5.2) times headings — and
// the best candidate per place is kept. Particles are then seeded around the best candidates
// (also used for sensor resetting when the filter loses track).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"
#include "localizer/localizer_options.h"
#include "localizer/region_maps.h"
#include "localizer/scan_model.h"

namespace rgnav::localizer {

struct Hypothesis
{
  int64_t region = 0;
  geometry::Pose2 region_from_base;
  double score = 0;   // sum of log p over the beams used
};

// A candidate moved to the best pose of a small local grid around it (hill climbing in steps
// of step_xy / step_theta, halved until below a tenth), rescored with `scorer`.
Hypothesis refine(const RegionModel& region, Hypothesis h, const std::vector<Eigen::Vector2d>& base_points,
                  const BeamScorer& scorer, double step_xy, double step_theta);

// The best `options.hypotheses` candidates, best first.
std::vector<Hypothesis> global_search(const RegionMaps& maps, const std::vector<Eigen::Vector2d>& base_points,
                                      const GlobalOptions& options, const ScanModel& scan);

}  // namespace rgnav::localizer
