#include "plan_pairs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "bench_stats.h"
#include "planner/global_planner.h"
#include "planner/route.h"
#include "plan_stats.h"
#include "route_checks.h"
#include "standable_points.h"

namespace rgnav::plan_eval {

using Eigen::Vector2d;
using localize_eval::number_or_null;
using localize_eval::percentile;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double polyline_length_of_legs(const planner::Route& route)
{
  double l = 0;
  for (const auto& leg : route.legs) l += polyline_length(leg.points);
  return l;
}

nlohmann::json point_json(const RegionPoint& p) { return {{"region", p.region}, {"x", p.point.x()}, {"y", p.point.y()}}; }

}  // namespace

nlohmann::json run_pairs(const std::string& name, const rgmap::RgMap& map, const planner::PlannerOptions& po,
                         const ConfigSpace& space, const PairsOptions& options, std::mt19937_64& rng, const std::string& dir,
                         PairSamples* totals)
{
  PairSamples s;
  const double adapt = po.grid.adapt_distance;
  const double wanted = po.grid.robot_radius + po.grid.clearance_margin;
  planner::GlobalPlanner warm(po), cold(po);
  nlohmann::json j;
  auto t0 = std::chrono::steady_clock::now();
  warm.set_map(map);
  j["set_map_ms"] = ms_since(t0);
  // Every region planner built once (the planner builds them on first use; a running planner
  // has them), timed per region.
  std::vector<double> build_ms;
  StandableSampler sampler(warm);
  for (int64_t id : sampler.regions()) {
    t0 = std::chrono::steady_clock::now();
    warm.region_planner(id);
    build_ms.push_back(ms_since(t0));
  }
  j["regions"] = static_cast<int>(sampler.regions().size());
  j["region_planner_build_ms_p50"] = number_or_null(percentile(build_ms, 0.5));
  j["region_planner_build_ms_max"] = number_or_null(max_of(build_ms));
  double build_total = 0;
  for (double b : build_ms) build_total += b;
  j["region_planners_build_ms_total"] = build_total;
  rgmap::RgMap bumped = map;
  cold.set_map(bumped);
  for (int64_t id : sampler.regions()) cold.region_planner(id);

  GridSearch search(space);
  // Per region: the grid of it and the regions beside it (through gateways), searched for the
  // shortest path of one leg.
  struct Local
  {
    std::unique_ptr<ConfigSpace> space;
    std::unique_ptr<GridSearch> search;
  };
  std::map<int64_t, Local> locals;
  const auto local_search = [&](int64_t region) -> GridSearch& {
    auto& l = locals[region];
    if (!l.search) {
      std::set<int64_t> near{region};
      for (const auto& [gid, g] : map.gateways())
        if (!g.neutralized && g.region_b != 0) {
          const int64_t ga = map.resolve(g.region_a), gb = map.resolve(g.region_b);
          if (ga == region) near.insert(gb);
          if (gb == region) near.insert(ga);
        }
      l.space = std::make_unique<ConfigSpace>(compose_occupancy(map, space.grid().resolution, po.grid.passage_depth, &near),
                                              po.grid.robot_radius);
      l.search = std::make_unique<GridSearch>(*l.space);
    }
    return *l.search;
  };
  const Components comfortable(space, wanted);
  WallCost wall;
  wall.margin = po.grid.clearance_margin;
  wall.comfort = po.grid.comfort_width;
  wall.wall_cost = po.grid.wall_cost;
  wall.comfort_cost = po.grid.comfort_cost;
  std::vector<DrawnPair> drawn;
  const auto fail = [&](const std::string& kind, const RegionPoint& a, const RegionPoint& b, const std::string& why, bool reference) {
    if (s.failures.contains(kind) && s.failures[kind].size() >= kMaxFailuresPerKind) return;
    // Where the ends lie on the whole grid: its clearance there, and how far the nearest cell
    // the robot may stand on is.
    const auto on_grid = [&](const RegionPoint& p) {
      const Vector2d m = in_map(map, p);
      const Cell c = space.grid().cell_of(m);
      const auto f = space.nearest_free(c, 2.0);
      return nlohmann::json{{"map_xy", {m.x(), m.y()}},
                            {"clearance_m", space.clearance(c)},
                            {"nearest_free_m", f ? nlohmann::json((*f - c).cast<double>().norm() * space.grid().resolution) : nlohmann::json(nullptr)}};
    };
    nlohmann::json sa = point_json(a), sb = point_json(b);
    sa["grid"] = on_grid(a);
    sb["grid"] = on_grid(b);
    s.failures[kind].push_back({{"world", name}, {"start", sa}, {"goal", sb}, {"why", why}, {"reference_path", reference}});
  };

  for (int k = 0; k < options.pairs; ++k) {
    const auto a = sampler.sample(rng), b = sampler.sample(rng);
    if (!a || !b) throw std::runtime_error(name + ": no standable point found");
    ++s.pairs;
    planner::PlanRequest req;
    req.start_region = a->region;
    req.start = a->point;
    req.goal_region = b->region;
    req.goal = b->point;
    // Warm: as a running planner meets requests one after another.
    std::string why_warm;
    t0 = std::chrono::steady_clock::now();
    const auto warm_route = warm.plan(req, &why_warm);
    s.warm_ms.push_back(ms_since(t0));
    // Cold: no region path cached.
    ++bumped.version;
    cold.set_map(bumped);
    std::string why;
    planner::PlanStats stats;
    t0 = std::chrono::steady_clock::now();
    const auto route = cold.plan(req, &why, &stats);
    const double wall_ms = ms_since(t0);

    const Vector2d from = in_map(map, *a), to = in_map(map, *b);
    std::optional<GridPath> ref;
    if (search.connected(from, to, adapt)) {
      t0 = std::chrono::steady_clock::now();
      ref = search.shortest(from, to, adapt);
      s.reference_ms.push_back(ms_since(t0));
    }
    if (ref) {
      ++s.reference_paths;
      t0 = std::chrono::steady_clock::now();
      const auto grid = search.wall_cost_astar(from, to, adapt, wall);
      s.grid_ms.push_back(ms_since(t0));
      t0 = std::chrono::steady_clock::now();
      search.wall_cost_astar(from, to, adapt, wall, false);
      s.grid_dijkstra_ms.push_back(ms_since(t0));
      if (grid && ref->length > 1e-6) s.grid_length_ratio.push_back(grid->length / ref->length);
    }
    if (!!warm_route != !!route) fail("warm_cold_disagree", *a, *b, "warm and cold planners disagree: warm '" + why_warm + "', cold '" + why + "'", !!ref);
    if (!route) {
      (ref ? s.failures_with_reference : s.failures_without_reference)++;
      if (ref) fail("no_route", *a, *b, why, true);
      continue;
    }
    ++s.successes;
    s.global_ms.push_back(stats.global_ms);
    s.region_ms_in_plan.push_back(stats.region_ms);
    s.plan_ms.push_back(stats.global_ms + stats.region_ms);
    s.plan_wall_ms.push_back(wall_ms);
    s.searches.push_back(stats.searches);
    if (stats.region_paths == 0 && route->legs.size() > 1) ++s.cold_region_paths_zero;
    s.cost_s.push_back(route->cost_s);
    const CheckedRoute c = check_route(map, *route, *a, *b, adapt);
    if (!c.defect.empty()) {
      ++s.route_defects;
      fail("route_defect", *a, *b, "route defect: " + c.defect, !!ref);
    }
    double route_clearance = INFINITY;
    for (const auto& leg : route->legs) route_clearance = std::min(route_clearance, leg.min_clearance);
    s.route_min_clearance.push_back(route_clearance);
    const SampledClearance sc = sample_clearance(space, c.map_points, options.comfort_end_m);
    // A start or goal the robot cannot stand on is moved up to adapt_distance: the route's ends
    // may lie nearer a wall than the radius; beyond them it should not.
    const SampledClearance inner = sample_clearance(space, c.map_points, adapt);
    const double inner_min = inner.interior_min;
    s.sampled_min_clearance.push_back(inner_min);
    s.sampled_mean_clearance.push_back(sc.mean);
    if (inner_min < po.grid.robot_radius - space.grid().resolution - 1e-6) {
      ++s.routes_in_collision;
      fail("route_near_wall", *a, *b,
           "route passes " + std::to_string(inner_min) + " m from a wall of the whole grid at map " +
               std::to_string(inner.interior_min_at.x()) + " " + std::to_string(inner.interior_min_at.y()),
           !!ref);
    }
    // Targets as the planner cuts them for collision avoidance, over the whole route, compared
    // in the first leg's frame; the straight line between two targets should keep off walls.
    const auto targets = planner::cut_targets(*route, po.execution.target_spacing_min, po.execution.target_spacing_max);
    std::vector<Vector2d> in_first, in_map_frame;
    for (const auto& t : targets) {
      in_first.push_back(route->frame_of(0, t.leg) * t.pose.translation());
      in_map_frame.push_back(map.region(route->legs[t.leg].region_id)->map_from_region * t.pose.translation());
    }
    for (size_t t = 1; t < targets.size(); ++t) {
      const double d = (in_first[t] - in_first[t - 1]).norm();
      s.spacing.push_back(d);
      // The last spacing ends at the goal and may be short.
      if (d < po.execution.target_spacing_min - 1e-6 && t + 1 < targets.size()) ++s.spacing_below_min;
      const auto where = [&] {
        return " between targets " + std::to_string(t - 1) + " (leg " + std::to_string(targets[t - 1].leg) + ", arc " +
               std::to_string(targets[t - 1].arc) + ") and " + std::to_string(t) + " (leg " + std::to_string(targets[t].leg) +
               ", arc " + std::to_string(targets[t].arc) + ") of " + std::to_string(targets.size());
      };
      if (d > po.execution.target_spacing_max + 1e-6) {
        ++s.spacing_above_max;
        fail("target_spacing", *a, *b, "targets " + std::to_string(d) + " m apart" + where(), !!ref);
      }
      const double seg_clearance = sample_clearance(space, {in_map_frame[t - 1], in_map_frame[t]}, 0.0).min;
      if (seg_clearance < po.grid.robot_radius - 0.1) {
        ++s.target_segments_near_walls;
        fail("target_line_near_wall", *a, *b, "straight line " + std::to_string(seg_clearance) + " m from a wall" + where(), !!ref);
      }
    }
    if (!targets.empty()) {
      const Vector2d goal_in_first = route->frame_of(0, route->legs.size() - 1) * route->legs.back().points.back();
      const double gap = (in_first.back() - goal_in_first).norm();
      s.targets_goal_gap_max = std::max(s.targets_goal_gap_max, gap);
      if (gap > 1e-3) ++s.targets_not_reaching_goal;
    }
    if (!ref) {
      ++s.routes_without_reference;
      fail("route_without_reference", *a, *b, "rgnav found a route, the whole grid has no path", false);
      continue;
    }
    ++s.successes_with_reference;
    if (ref->length > 1e-6) {
      const double ratio = c.length / ref->length;
      s.length_ratio.push_back(ratio);
      // The detour split in two: each leg against the shortest path between its own ends
      // inside its region (and the regions beside it, as the planner's region grid sees them),
      // and the sum of those against the whole grid's (the RG graph's choice of regions and
      // crossing points: the whole grid may join two regions where the map has no gateway).
      double legs_reference = 0;
      for (const auto& leg : route->legs) {
        const Vector2d leg_from = map.region(leg.region_id)->map_from_region * leg.points.front();
        const Vector2d leg_to = map.region(leg.region_id)->map_from_region * leg.points.back();
        const auto r = local_search(leg.region_id).shortest(leg_from, leg_to, adapt);
        legs_reference += r ? r->length : (leg_to - leg_from).norm();
      }
      const double ratio_legs = legs_reference > 1e-6 ? polyline_length_of_legs(*route) / legs_reference : NAN;
      if (!std::isnan(ratio_legs)) {
        s.length_ratio_legs.push_back(ratio_legs);
        s.graph_ratio.push_back(legs_reference / ref->length);
      }
      if (ratio > options.long_route_ratio)
        fail("long_route", *a, *b,
             "route " + std::to_string(c.length) + " m, the reference " + std::to_string(ref->length) +
                 " m, the legs' own shortest paths " + std::to_string(legs_reference) + " m over " +
                 std::to_string(route->legs.size()) + " legs",
             true);
    }
    if (comfortable.joined(from, to, options.comfort_end_m)) {
      ++s.comfort_pairs;
      if (sc.interior_min >= wanted - space.grid().resolution) ++s.comfort_ok;
    }
    if (static_cast<int>(drawn.size()) < options.pictures) drawn.push_back({c.map_points, ref->points});
  }

  // Region paths on their own: two standable points of one random region.
  for (int k = 0; k < options.region_pairs; ++k) {
    const auto a = sampler.sample(rng);
    if (!a) break;
    const auto b = sampler.sample_in(a->region, rng);
    if (!b) continue;
    const auto* rp = warm.region_planner(a->region);
    ++s.region_path_tries;
    t0 = std::chrono::steady_clock::now();
    const auto path = rp->plan(a->point, b->point);
    s.region_path_ms.push_back(ms_since(t0));
    if (!path) continue;
    ++s.region_path_ok;
    // Against the whole grid's shortest between the same points (which may leave the region).
    const auto ref = search.shortest(in_map(map, *a), in_map(map, *b), adapt);
    if (ref && ref->length > 0.5) s.region_path_length_ratio.push_back(path->length / ref->length);
  }

  if (options.pictures > 0 && !drawn.empty()) {
    std::filesystem::create_directories(dir);
    draw_routes(space, drawn, dir + "/routes.png");
  }
  nlohmann::json summary = s.summary(po);
  for (auto it = j.begin(); it != j.end(); ++it) summary[it.key()] = it.value();
  totals->add(s);
  return summary;
}

}  // namespace rgnav::plan_eval
