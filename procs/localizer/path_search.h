// The check before a claim: every place and heading of the map scored on the views of the
// robot's path (view_path.h), not only the places the newest scan search kept.
//
// The scan search (global_search.h) keeps, per place, the heading the current scan fits best on
// its grid, and only its best few hundred places: on a floor made of turned copies of one wing,
// the copy the robot is really in can drop out of those (its scan fits a dozen hallway cells
// equally; at a heading a grid step off, the far end of the path misses its walls), and then the
// claim test never meets it and claims a copy turned by 72 degrees. Here the whole path, as
// one rigid set of points, is matched at every freespace cell and at headings twice as fine as
// the scan search's. The sum of log p only falls as points are added (log p <= 0), so a
// candidate is dropped as soon as its partial sum falls below the worst of the best kept
// (branch and bound): the exact best places for the cost of a few points at most candidates.
#pragma once

#include <functional>
#include <vector>

#include "localizer/global_search.h"
#include "localizer/localizer_options.h"
#include "localizer/path_score.h"
#include "localizer/region_maps.h"

namespace rgnav::localizer {

struct PathSearchOptions
{
  int headings = 72;          // headings per place
  int views = 6;              // views of the path used, spread over it (its oldest and newest among them)
  int beams_per_view = 30;    // points per view
  int keep = 8;               // distinct places returned
  int pool = 400;             // best candidates (one per cell) kept while searching, before the distinct places are picked
};

// The `keep` best distinct places ("the robot stands here now") for the views, best first,
// scored with `scorer` in each candidate's region (its stacked field: own lines and the
// neighbours'). `distinct(a, b)` says whether two candidates are different places. `progress`
// (if set) is called after each region: the search may take most of a second on a large map, and
// the node's heartbeat shows the supervisor that it is busy, not hung.
std::vector<Hypothesis> path_search(const RegionMaps& maps, const std::vector<PlacedView>& views, const BeamScorer& scorer,
                                    const PathSearchOptions& options,
                                    const std::function<bool(const Hypothesis&, const Hypothesis&)>& distinct,
                                    const std::function<void()>& progress = nullptr);

}  // namespace rgnav::localizer
