// Where each region of a map built by rgnav's own pipeline lies in the simulated world. The
// localizer estimates poses in region frames, and a region's line map carries the SLAM error of
// the scans it was built from; a single rigid fit of the whole map would count the map's global
// drift as localization error. So every region gets its own fit: its scans' positions (in the
// region frame) against their true positions. A region with too few scans takes the whole
// map's fit.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "geometry/pose2.h"
#include "offline_run.h"

namespace rgnav::localize_eval {

struct TruthFrames
{
  geometry::Pose2 world_from_map;
  std::map<int64_t, geometry::Pose2> world_from_region;
  std::map<int64_t, double> fit_rmse;          // [m] per region
  std::map<int64_t, int> fit_points;           // scans the fit used (0: the whole map's fit)
  const rgmap::RgMap* map = nullptr;

  // The true pose in region r's frame.
  geometry::Pose2 in_region(int64_t region, const geometry::Pose2& world_from_base) const;
  // A region whose freespace holds the true position: `prefer` if it does, else the lowest id; 0 if none.
  int64_t region_at(const geometry::Pose2& world_from_base, int64_t prefer = 0) const;
};

TruthFrames fit_truth_frames(const rgmap_pipeline::OfflineRun& run, const std::vector<geometry::Pose2>& truth_at_node,
                             const geometry::Pose2& base_from_laser);

}  // namespace rgnav::localize_eval
