// Scoring the views of the robot's path (view_path.h) at a candidate pose "the robot stands
// here now". Each view is scored in the region that holds the place it was taken from, reached
// through the gateways (as a particle is handed over, diss. 5.3): a path of a few metres often
// began in another region, and its early views see walls that the current region's stacked map
// (its own lines and its direct neighbours') does not hold. Scored against the current region
// alone, the true pose would lose to a look-alike whose region happens to hold those walls.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"
#include "localizer/region_maps.h"
#include "localizer/scan_model.h"

namespace rgnav::localizer {

struct PlacedView
{
  geometry::Pose2 now_from_then;                   // the view's base pose in the current base frame
  const std::vector<Eigen::Vector2d>* points = nullptr;   // its end points, its own base frame
};

// The region (and the pose in it) holding a pose given in `region`'s frame: `region` itself if
// the pose lies in its freespace and within `bbox_margin` of its measurement rectangle, else
// the first region up to `hops` gateways away that does; `region` if none does.
std::pair<const RegionModel*, geometry::Pose2> holding_region(const RegionMaps& maps, int64_t region,
                                                              const geometry::Pose2& region_from_base, double bbox_margin,
                                                              int hops = 2);

// Sum of log p (scorer) of every view's points, each view in the region holding its place.
double path_score(const RegionMaps& maps, const BeamScorer& scorer, int64_t region, const geometry::Pose2& region_from_base,
                  const std::vector<PlacedView>& views, double bbox_margin);

// One beam of a view scored at a candidate pose, and whether the map can judge it there: its end
// lies near one of the holding region's lines (the map says wall) or in the freespace the
// region's own scans carved (the map says no wall). Elsewhere the map has not seen the spot: a
// wall the robot sees there may simply be missing from the map.
struct BeamFit
{
  double log_p = 0;
  bool known = false;
};

// Every beam of the views at the pose (as path_score), in view order. `near_line`: [m] a beam
// end this close to a line counts as judged by the map. `through_gateways`: the freespace a beam
// is judged in is the stacked map's, the region's and its neighbours' beyond the gateways (as
// the field stacks their lines); false: the region's own (a beam through a doorway is then
// unjudged unless it ends near a line).
std::vector<BeamFit> path_beam_fits(const RegionMaps& maps, const BeamScorer& scorer, int64_t region,
                                    const geometry::Pose2& region_from_base, const std::vector<PlacedView>& views,
                                    double bbox_margin, double near_line, bool through_gateways = false);

// How much better the beams fit at `a` than at `b` (sum of log p differences, equal-length
// lists of the same beams), over the beams both maps can judge: evidence that the two maps
// themselves tell apart, not a gap in one of them. `beams`: how many beams that sum counted.
struct JudgedDifference
{
  double log_ratio = 0;
  int beams = 0;
};
JudgedDifference jointly_judged(const std::vector<BeamFit>& a, const std::vector<BeamFit>& b);
inline double jointly_judged_difference(const std::vector<BeamFit>& a, const std::vector<BeamFit>& b)
{
  return jointly_judged(a, b).log_ratio;
}

}  // namespace rgnav::localizer
