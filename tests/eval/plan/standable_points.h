// Random start and goal points for the planning benchmark: a random live region (each region
// equally likely), a random point of its freespace where rgnav's region planner says the robot
// can stand (RegionPlanner::standable).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <vector>

#include "geometry/pose2.h"
#include "planner/global_planner.h"
#include "rgmap/rg_map.h"

namespace rgnav::plan_eval {

struct RegionPoint
{
  int64_t region = 0;
  Eigen::Vector2d point{0, 0};   // region frame
};

class StandableSampler
{
 public:
  // The live regions of the planner's map with at least one free freespace cell.
  explicit StandableSampler(planner::GlobalPlanner& planner);

  // A standable point of a random region (nullopt after `tries` misses).
  std::optional<RegionPoint> sample(std::mt19937_64& rng, int tries = 200);
  // A standable point of region `region`.
  std::optional<RegionPoint> sample_in(int64_t region, std::mt19937_64& rng, int tries = 200);
  const std::vector<int64_t>& regions() const { return regions_; }

 private:
  planner::GlobalPlanner& planner_;
  std::vector<int64_t> regions_;
  std::map<int64_t, std::vector<std::pair<int, int>>> free_cells_;   // freespace bitmap cells
};

// The point in the map frame (map_from_region of its region).
Eigen::Vector2d in_map(const rgmap::RgMap& map, const RegionPoint& p);

}  // namespace rgnav::plan_eval
