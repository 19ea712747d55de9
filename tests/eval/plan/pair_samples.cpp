// PairSamples: pooling and the JSON figures of the planning-alone part (plan_pairs.h).
#include <algorithm>
#include <cmath>

#include "bench_stats.h"
#include "plan_pairs.h"
#include "plan_stats.h"

namespace rgnav::plan_eval {

using localize_eval::number_or_null;
using localize_eval::percentile;

void PairSamples::add(const PairSamples& o)
{
  pairs += o.pairs;
  reference_paths += o.reference_paths;
  successes += o.successes;
  successes_with_reference += o.successes_with_reference;
  failures_with_reference += o.failures_with_reference;
  failures_without_reference += o.failures_without_reference;
  routes_without_reference += o.routes_without_reference;
  route_defects += o.route_defects;
  routes_in_collision += o.routes_in_collision;
  cold_region_paths_zero += o.cold_region_paths_zero;
  const auto cat = [](std::vector<double>& a, const std::vector<double>& b) { a.insert(a.end(), b.begin(), b.end()); };
  cat(global_ms, o.global_ms);
  cat(region_ms_in_plan, o.region_ms_in_plan);
  cat(plan_ms, o.plan_ms);
  cat(plan_wall_ms, o.plan_wall_ms);
  cat(warm_ms, o.warm_ms);
  cat(searches, o.searches);
  cat(length_ratio, o.length_ratio);
  cat(length_ratio_legs, o.length_ratio_legs);
  cat(graph_ratio, o.graph_ratio);
  cat(cost_s, o.cost_s);
  cat(grid_ms, o.grid_ms);
  cat(grid_dijkstra_ms, o.grid_dijkstra_ms);
  cat(grid_length_ratio, o.grid_length_ratio);
  cat(reference_ms, o.reference_ms);
  cat(route_min_clearance, o.route_min_clearance);
  cat(sampled_min_clearance, o.sampled_min_clearance);
  cat(sampled_mean_clearance, o.sampled_mean_clearance);
  comfort_pairs += o.comfort_pairs;
  comfort_ok += o.comfort_ok;
  cat(region_path_ms, o.region_path_ms);
  cat(region_path_length_ratio, o.region_path_length_ratio);
  region_path_tries += o.region_path_tries;
  region_path_ok += o.region_path_ok;
  cat(spacing, o.spacing);
  spacing_below_min += o.spacing_below_min;
  spacing_above_max += o.spacing_above_max;
  targets_not_reaching_goal += o.targets_not_reaching_goal;
  target_segments_near_walls += o.target_segments_near_walls;
  targets_goal_gap_max = std::max(targets_goal_gap_max, o.targets_goal_gap_max);
  for (auto it = o.failures.begin(); it != o.failures.end(); ++it)
    for (const auto& f : it.value())
      if (!failures.contains(it.key()) || failures[it.key()].size() < 2 * kMaxFailuresPerKind) failures[it.key()].push_back(f);
}

nlohmann::json PairSamples::summary(const planner::PlannerOptions& options) const
{
  nlohmann::json j;
  j["pairs"] = pairs;
  j["reference_paths"] = reference_paths;
  j["success_ratio"] = number_or_null(reference_paths ? static_cast<double>(successes_with_reference) / reference_paths : NAN);
  j["failures_where_a_path_exists"] = failures_with_reference;
  j["no_path_both"] = failures_without_reference;
  j["routes_where_reference_has_none"] = routes_without_reference;
  j["route_defects"] = route_defects;
  j["routes_in_collision"] = routes_in_collision;
  // Cold: the planner's region-path cache emptied before every request (a new map version),
  // so every region path the route needs is planned; warm: one planner over all pairs in turn.
  j["global_ms_p50"] = number_or_null(percentile(global_ms, 0.5));
  j["global_ms_p99"] = number_or_null(percentile(global_ms, 0.99));
  j["global_ms_max"] = number_or_null(max_of(global_ms));
  j["plan_region_ms_p50"] = number_or_null(percentile(region_ms_in_plan, 0.5));
  j["plan_ms_p50"] = number_or_null(percentile(plan_ms, 0.5));
  j["plan_ms_p99"] = number_or_null(percentile(plan_ms, 0.99));
  j["plan_wall_ms_p50"] = number_or_null(percentile(plan_wall_ms, 0.5));
  j["plan_wall_ms_p99"] = number_or_null(percentile(plan_wall_ms, 0.99));
  j["plan_warm_wall_ms_p50"] = number_or_null(percentile(warm_ms, 0.5));
  j["plan_warm_wall_ms_p99"] = number_or_null(percentile(warm_ms, 0.99));
  j["searches_mean"] = number_or_null(mean(searches));
  j["cold_plans_without_region_paths"] = cold_region_paths_zero;
  j["region_ms_p50"] = number_or_null(percentile(region_path_ms, 0.5));
  j["region_ms_p99"] = number_or_null(percentile(region_path_ms, 0.99));
  j["region_ms_max"] = number_or_null(max_of(region_path_ms));
  j["region_paths"] = region_path_tries;
  j["region_path_success_ratio"] = number_or_null(region_path_tries ? static_cast<double>(region_path_ok) / region_path_tries : NAN);
  j["region_path_length_ratio_p50"] = number_or_null(percentile(region_path_length_ratio, 0.5));
  j["region_path_length_ratio_max"] = number_or_null(max_of(region_path_length_ratio));
  j["length_ratio_p50"] = number_or_null(percentile(length_ratio, 0.5));
  j["length_ratio_p95"] = number_or_null(percentile(length_ratio, 0.95));
  j["length_ratio_max"] = number_or_null(max_of(length_ratio));
  j["length_ratio_over_1_05"] = static_cast<int>(std::count_if(length_ratio.begin(), length_ratio.end(), [](double r) { return r > 1.05; }));
  // The detour split: the legs against their own shortest paths inside their regions (region
  // paths and their smoothing), and those summed against the whole grid's shortest (the RG
  // graph's regions and crossing points).
  j["length_ratio_legs_p50"] = number_or_null(percentile(length_ratio_legs, 0.5));
  j["length_ratio_legs_p95"] = number_or_null(percentile(length_ratio_legs, 0.95));
  j["length_ratio_legs_max"] = number_or_null(max_of(length_ratio_legs));
  j["graph_ratio_p50"] = number_or_null(percentile(graph_ratio, 0.5));
  j["graph_ratio_p95"] = number_or_null(percentile(graph_ratio, 0.95));
  j["graph_ratio_max"] = number_or_null(max_of(graph_ratio));
  j["reference_ms_p50"] = number_or_null(percentile(reference_ms, 0.5));
  j["grid_astar_ms_p50"] = number_or_null(percentile(grid_ms, 0.5));
  j["grid_astar_ms_p99"] = number_or_null(percentile(grid_ms, 0.99));
  j["grid_dijkstra_ms_p50"] = number_or_null(percentile(grid_dijkstra_ms, 0.5));
  j["grid_astar_length_ratio_p50"] = number_or_null(percentile(grid_length_ratio, 0.5));
  j["grid_astar_length_ratio_max"] = number_or_null(max_of(grid_length_ratio));
  const double rg = percentile(plan_ms, 0.5);
  j["speedup_vs_grid"] = number_or_null(rg > 0 ? percentile(grid_ms, 0.5) / rg : NAN);
  const double rgw = percentile(plan_wall_ms, 0.5);
  j["speedup_vs_grid_wall"] = number_or_null(rgw > 0 ? percentile(grid_ms, 0.5) / rgw : NAN);
  j["clearance_min_m"] = number_or_null(min_of(route_min_clearance));
  j["clearance_route_min_mean_m"] = number_or_null(mean(route_min_clearance));
  j["clearance_sampled_min_m"] = number_or_null(min_of(sampled_min_clearance));
  j["clearance_sampled_mean_m"] = number_or_null(mean(sampled_mean_clearance));
  j["clearance_wanted_m"] = options.grid.robot_radius + options.grid.clearance_margin;
  j["clearance_where_it_fits_pairs"] = comfort_pairs;
  j["clearance_where_it_fits_ratio"] = number_or_null(comfort_pairs ? static_cast<double>(comfort_ok) / comfort_pairs : NAN);
  j["target_spacing_min_m"] = number_or_null(min_of(spacing));
  j["target_spacing_max_m"] = number_or_null(max_of(spacing));
  j["target_spacing_mean_m"] = number_or_null(mean(spacing));
  j["target_spacings_below_min"] = spacing_below_min;
  j["target_spacings_above_max"] = spacing_above_max;
  j["targets_not_reaching_goal"] = targets_not_reaching_goal;
  j["target_segments_near_walls"] = target_segments_near_walls;
  j["targets_goal_gap_max_m"] = targets_goal_gap_max;
  j["failures"] = failures;
  return j;
}

}  // namespace rgnav::plan_eval
