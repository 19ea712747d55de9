// Planning alone on one map: random start/goal pairs planned by rgnav's GlobalPlanner and by
// the whole-building yardsticks on the same occupancy (grid_search.h), and region paths timed
// on their own. Each world gives its JSON section and adds its samples to the totals.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "grid_search.h"
#include "occupancy_grid.h"
#include "planner/planner_options.h"
#include "rgmap/rg_map.h"

namespace rgnav::plan_eval {

struct PairsOptions
{
  int pairs = 250;               // start/goal pairs
  int region_pairs = 500;        // region paths timed on their own
  int pictures = 8;              // pairs drawn into routes.png (0: no picture)
  double comfort_end_m = 1.0;    // [m] route ends left out of the clearance-where-it-fits check
  double long_route_ratio = 1.5; // a route longer than this times the reference is listed among the failures
};

// Failures listed per kind and world (all are counted).
constexpr size_t kMaxFailuresPerKind = 5;

// Everything measured, pooled over worlds.
struct PairSamples
{
  int pairs = 0;
  int reference_paths = 0;            // pairs with a reference path (a path exists)
  int successes = 0;                  // rgnav found a route
  int successes_with_reference = 0;
  int failures_with_reference = 0;    // rgnav failed where a path exists
  int failures_without_reference = 0; // both found none
  int routes_without_reference = 0;   // rgnav found a route where the reference found none
  int route_defects = 0;              // routes whose legs do not join, miss the start or goal, or whose length disagrees
  int routes_in_collision = 0;        // routes passing a cell of the whole grid more than a cell nearer than the radius to a wall (ends within adapt_distance left out)
  int cold_region_paths_zero = 0;     // cold plans that reused cached region paths (the cache was not cleared)
  std::vector<double> global_ms, region_ms_in_plan, plan_ms, plan_wall_ms, warm_ms;   // cold PlanStats, cold wall, warm wall
  std::vector<double> searches;
  std::vector<double> length_ratio, cost_s;
  std::vector<double> length_ratio_legs;   // legs / their own shortest paths inside their regions
  std::vector<double> graph_ratio;         // those shortest paths summed / the whole grid's reference
  std::vector<double> grid_ms, grid_dijkstra_ms, grid_length_ratio, reference_ms;
  std::vector<double> route_min_clearance, sampled_min_clearance, sampled_mean_clearance;
  int comfort_pairs = 0, comfort_ok = 0;   // the passage allows radius + margin all the way / the route keeps it
  std::vector<double> region_path_ms, region_path_length_ratio;
  int region_path_tries = 0, region_path_ok = 0;
  std::vector<double> spacing;
  int spacing_below_min = 0, spacing_above_max = 0, targets_not_reaching_goal = 0;
  int target_segments_near_walls = 0; // straight lines between targets passing nearer than radius - 0.1 m to a wall
  double targets_goal_gap_max = 0;    // [m] last target to the goal
  nlohmann::json failures = nlohmann::json::object();  // by kind, the first few, for reproduction

  void add(const PairSamples& o);
  // The JSON figures of these samples (per world and over all).
  nlohmann::json summary(const planner::PlannerOptions& options) const;
};

// Plans `options.pairs` random pairs of standable points of `map` (plus the region paths) and
// returns the world's JSON; figures under `dir` (routes.png).
nlohmann::json run_pairs(const std::string& name, const rgmap::RgMap& map, const planner::PlannerOptions& planner_options,
                         const ConfigSpace& space, const PairsOptions& options, std::mt19937_64& rng, const std::string& dir,
                         PairSamples* totals);

}  // namespace rgnav::plan_eval
