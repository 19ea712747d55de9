#include "closed_loop.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "bench_stats.h"
#include "grid_search.h"
#include "plan_stats.h"
#include "planned_drive.h"
#include "standable_points.h"

namespace rgnav::plan_eval {

using Eigen::Vector2d;
using geometry::Pose2;
using localize_eval::BenchWorld;
using localize_eval::number_or_null;
using localize_eval::percentile;

namespace {

// The true pose in the map frame, through the region holding it.
std::optional<Vector2d> truth_in_map(const BenchWorld& w, const Pose2& truth, int64_t prefer)
{
  const int64_t r = w.frames.region_at(truth, prefer);
  const int64_t use = r ? r : prefer;
  const auto* region = w.map.region(use);
  if (!region || !w.frames.world_from_region.count(use)) return std::nullopt;
  return region->map_from_region * w.frames.in_region(use, truth).translation();
}

// One line of PLAN_TRACE: where the robot is, what collision avoidance and the planner say.
void trace_line(const std::string& what, const PlannedDrive& d, const Vector2d& goal_world)
{
  std::cerr << what << " t=" << d.sim().time_s() << " at " << d.truth().x() << "," << d.truth().y() << " r" << d.region()
            << " ca " << collision_avoidance::mode_name(d.ca().mode()) << " '" << d.ca().status() << "' goal "
            << goal_world.x() << "," << goal_world.y() << " targets" << d.targets_text(3) << " nearest person "
            << d.nearest_person() << " wall " << d.sim().clearance({d.truth().x(), d.truth().y()}, 3.0) << " planner "
            << planner::to_string(d.planner().status()) << " route";
  for (const auto& leg : d.planner().route().legs) std::cerr << " r" << leg.region_id;
  std::cerr << " (" << d.planner().reason() << ")";
  std::cerr << "\n";
}

// Whether the RG graph joins two regions without gateway `without`.
bool graph_joins(const rgmap::RgMap& map, int64_t from, int64_t to, int64_t without)
{
  std::set<int64_t> seen{map.resolve(from)};
  std::vector<int64_t> open{map.resolve(from)};
  while (!open.empty()) {
    const int64_t r = open.back();
    open.pop_back();
    if (r == map.resolve(to)) return true;
    for (const auto& [id, g] : map.gateways()) {
      if (id == without || g.neutralized || g.region_b == 0) continue;
      const int64_t a = map.resolve(g.region_a), b = map.resolve(g.region_b);
      const int64_t next = a == r ? b : b == r ? a : 0;
      if (next && seen.insert(next).second) open.push_back(next);
    }
  }
  return false;
}

std::vector<Vector2d> door_line(const Vector2d& a, const Vector2d& b, double extend)
{
  const Vector2d d = (b - a).normalized();
  return {a - extend * d, b + extend * d};
}

nlohmann::json run_goals(const BenchWorld& w, const ConfigSpace& space, const ClosedLoopSetup& setup,
                         const ClosedLoopOptions& options, std::mt19937_64& rng, ClosedLoopSamples* s)
{
  sim::World world = w.world;
  sim::SimulatorOptions so = setup.sim;
  so.seed = rng();
  PlannedDrive d(world, so, w, setup);
  StandableSampler sampler(d.planner().global());
  GridSearch search(space);
  const double adapt = setup.planner.grid.adapt_distance;
  const double speed = setup.planner.execution.max_speed;
  const double body_room = setup.planner.grid.robot_radius + options.body_margin;
  nlohmann::json goals = nlohmann::json::array();
  for (int k = 0; k < 10; ++k) d.step();   // first odometry and scans
  const int64_t collisions0 = d.sim().collisions();
  for (int g = 0; g < options.goals; ++g) {
    // A standable point of a region placed in the world, away from the robot.
    std::optional<RegionPoint> target;
    Vector2d goal_world(0, 0);
    for (int tries = 0; tries < 200 && !target; ++tries) {
      auto p = sampler.sample(rng);
      if (!p || !w.frames.world_from_region.count(p->region)) continue;
      goal_world = w.frames.world_from_region.at(p->region) * p->point;
      if ((goal_world - d.truth().translation()).norm() < options.min_goal_distance) continue;
      // The robot's body must fit there in the true world: the map holds what a laser at 0.4 m
      // sees, and a goal under a table top is free in the map but out of reach.
      if (d.sim().clearance(goal_world, 2.0) < body_room) {
        ++s->goals_out_of_reach;
        continue;
      }
      target = p;
    }
    if (!target) throw std::runtime_error(w.name + ": no goal found");
    const auto start_map = truth_in_map(w, d.truth(), d.region());
    const Vector2d goal_map = in_map(w.map, *target);
    std::optional<GridPath> ref;
    if (start_map && search.connected(*start_map, goal_map, adapt)) ref = search.shortest(*start_map, goal_map, adapt);
    const double straight = (goal_world - d.truth().translation()).norm();
    // The time allowed: timeout_factor x the longer of the reference and the planner's first
    // route at its speed (a detour the RG graph forces costs SPL, not success).
    const double reference_m = ref ? ref->length : straight;
    double timeout_s = options.timeout_factor * reference_m / speed + options.timeout_extra_s;
    double first_route_m = NAN;

    planner::NavGoal ng;
    ng.goal_id = g + 1;
    ng.region_id = target->region;
    ng.has_pose = true;
    ng.region_from_goal = Pose2(target->point, 0.0);
    ng.position_tolerance = options.position_tolerance;
    ng.heading_tolerance = 3.2;
    const double t0 = d.sim().time_s(), dist0 = d.true_distance();
    const int64_t coll0 = d.sim().collisions();
    const Vector2d start_world = d.truth().translation();
    d.take_contacts();
    d.planner().set_goal(ng, d.sim().now_utime());
    std::string outcome = "timeout";
    double next_trace = t0, first_no_path_s = NAN;
    int no_path_reports = 0;
    auto last_status = planner::GoalStatus::kNone;
    while (d.sim().time_s() - t0 < timeout_s) {
      d.step();
      if (std::isnan(first_route_m) && !d.planner().route().empty()) {
        first_route_m = d.planner().route().length;
        timeout_s = options.timeout_factor * std::max(reference_m, first_route_m) / speed + options.timeout_extra_s;
      }
      const auto st = d.planner().status();
      if (st == planner::GoalStatus::kReached) {
        outcome = (d.truth().translation() - goal_world).norm() <= options.reached_truth_m ? "reached" : "reached_elsewhere";
        break;
      }
      // NO_PATH keeps the goal in the planner, which plans it again when a closed mark expires:
      // the goal goes on to its timeout, and ends NO_PATH if that is what the planner says then.
      if (st == planner::GoalStatus::kNoPath && last_status != st) {
        ++no_path_reports;
        if (std::isnan(first_no_path_s)) first_no_path_s = d.sim().time_s() - t0;
      }
      last_status = st;
      if (options.trace && d.sim().time_s() >= next_trace) {
        next_trace += 1.0;
        trace_line(w.name + " goal " + std::to_string(ng.goal_id), d, goal_world);
      }
    }
    if (outcome == "timeout" && d.planner().status() == planner::GoalStatus::kNoPath) outcome = "no_path";
    if (outcome != "reached" && outcome != "reached_elsewhere") d.planner().cancel(ng.goal_id, d.sim().now_utime());
    s->goals_with_no_path_report += no_path_reports > 0;
    const double time_s = d.sim().time_s() - t0, driven = d.true_distance() - dist0;
    ++s->goals;
    const bool ok = outcome == "reached";
    s->successes += ok;
    s->no_path += outcome == "no_path";
    s->timeouts += outcome == "timeout";
    s->reached_elsewhere += outcome == "reached_elsewhere";
    // The planner counts replans per goal.
    const int64_t replans = d.planner().replans();
    s->replans += replans;
    if (ref) {
      s->spl.push_back(ok ? ref->length / std::max(ref->length, driven) : 0.0);
      if (ok) {
        s->time_ratio.push_back(time_s / std::max(1e-6, ref->length / speed));
        if (ref->length > 0.1) s->driven_ratio.push_back(driven / ref->length);
      }
    } else {
      ++s->without_reference;
    }
    if (ok) s->time_s.push_back(time_s);
    nlohmann::json gj = {{"goal", ng.goal_id},
                         {"outcome", outcome},
                         {"region", target->region},
                         {"goal_region_xy", {target->point.x(), target->point.y()}},
                         {"start_world", {start_world.x(), start_world.y()}},
                         {"goal_world", {goal_world.x(), goal_world.y()}},
                         {"shortest_m", ref ? nlohmann::json(ref->length) : nlohmann::json(nullptr)},
                         {"first_route_m", number_or_null(first_route_m)},
                         {"timeout_s", timeout_s},
                         {"driven_m", driven},
                         {"time_s", time_s},
                         {"replans", replans},
                         {"collisions", d.sim().collisions() - coll0},
                         {"no_path_reports", no_path_reports},
                         {"first_no_path_s", number_or_null(first_no_path_s)}};
    if (!ok) gj["final_world"] = {d.truth().x(), d.truth().y()};
    const auto contacts = d.take_contacts();
    if (!contacts.empty()) gj["contacts"] = contacts;
    for (const auto& c : contacts) s->contacts.push_back(c);
    if (options.trace)
      std::cerr << w.name << " goal " << gj.dump() << "\n";
    goals.push_back(gj);
  }
  s->collisions += d.sim().collisions() - collisions0;
  s->sim_s += d.sim().time_s();
  s->planner_cpu_s += d.planner_cpu_s();
  nlohmann::json j;
  j["goal_log"] = goals;
  j["planner_reports"] = d.reasons();
  return j;
}

// Door cases: a gateway of the map closed by a door leaf in the simulated world.
nlohmann::json run_door_cases(const BenchWorld& w, const ConfigSpace& space, const ClosedLoopSetup& setup,
                              const ClosedLoopOptions& options, std::mt19937_64& rng, ClosedLoopSamples* s)
{
  nlohmann::json cases = nlohmann::json::array();
  std::vector<const rgmap::Gateway*> candidates;
  for (const auto& [id, g] : w.map.gateways()) {
    if (g.neutralized || g.region_b == 0 || g.gateway_points.size() < 2 || g.crossing_points.empty()) continue;
    if (g.cls != rgmap::GatewayClass::kDoor && g.cls != rgmap::GatewayClass::kNarrowPassage) continue;
    const int64_t a = w.map.resolve(g.region_a), b = w.map.resolve(g.region_b);
    if (a == b || !w.frames.world_from_region.count(a) || !w.frames.world_from_region.count(b)) continue;
    candidates.push_back(&g);
  }
  std::shuffle(candidates.begin(), candidates.end(), rng);
  planner::GlobalPlanner probe(setup.planner);
  probe.set_map(w.map);
  StandableSampler sampler(probe);
  const double adapt = setup.planner.grid.adapt_distance;
  // The world as it is at the start (its clearance says where the robot's body fits).
  const sim::Simulator reference_sim(w.world, setup.sim);
  for (const auto* g : candidates) {
    if (static_cast<int>(cases.size()) >= options.door_cases) break;
    const int64_t a = w.map.resolve(g->region_a), b = w.map.resolve(g->region_b);
    const auto area = [&](int64_t r) { return w.map.region(r)->freespace.features().area; };
    // The goal in the smaller region (the room behind the door), the start in the other.
    const int64_t room = area(a) <= area(b) ? a : b, other = room == a ? b : a;
    const Pose2 world_from_a = w.frames.world_from_region.at(a), map_from_a = w.map.region(a)->map_from_region;
    const Vector2d cross_world = world_from_a * g->crossing_points.front();
    std::optional<RegionPoint> goal, start;
    const double body_room = setup.planner.grid.robot_radius + options.body_margin;
    for (int k = 0; k < 200 && !goal; ++k) {
      auto p = sampler.sample_in(room, rng, 20);
      if (!p) continue;
      const Vector2d at = w.frames.world_from_region.at(room) * p->point;
      if ((at - cross_world).norm() >= 1.0 && reference_sim.clearance(at, 2.0) >= body_room) goal = p;
    }
    for (int k = 0; k < 200 && !start; ++k) {
      auto p = sampler.sample_in(other, rng, 20);
      if (!p) continue;
      const Vector2d at = w.frames.world_from_region.at(other) * p->point;
      const double dist = (at - cross_world).norm();
      if (dist >= 1.5 && dist <= 6.0 && reference_sim.clearance(at, 2.0) >= body_room) start = p;
    }
    if (!goal || !start) continue;
    // The door leaf across the gateway, 0.3 m into the walls on both sides.
    const auto leaf_world = door_line(world_from_a * g->gateway_points[0], world_from_a * g->gateway_points[1], 0.3);
    const auto leaf_map = door_line(map_from_a * g->gateway_points[0], map_from_a * g->gateway_points[1], 0.3);
    OccupancyGrid closed_grid = space.grid();
    closed_grid.draw_occupied(leaf_map[0], leaf_map[1]);
    const ConfigSpace closed(std::move(closed_grid), space.robot_radius());
    GridSearch closed_search(closed);
    const bool way_round_in_grid = closed_search.connected(in_map(w.map, *start), in_map(w.map, *goal), adapt);
    // The planner can only go round through the map's gateways.
    const bool way_round = way_round_in_grid && graph_joins(w.map, start->region, goal->region, g->id);

    sim::World world = w.world;
    sim::Door door;
    door.name = "bench_closed_door";
    door.hinge = leaf_world[0];
    door.latch = leaf_world[1];
    door.open = false;
    door.schedule = {{options.door_reopen_s, true}};
    world.doors.push_back(door);
    const Vector2d start_world = w.frames.world_from_region.at(other) * start->point;
    const Vector2d to_door = cross_world - start_world;
    world.start = sim::Pose2{start_world.x(), start_world.y(), std::atan2(to_door.y(), to_door.x())};
    sim::SimulatorOptions so = setup.sim;
    so.seed = rng();
    PlannedDrive d(world, so, w, setup);
    for (int k = 0; k < 10; ++k) d.step();
    planner::NavGoal ng;
    ng.goal_id = 1;
    ng.region_id = goal->region;
    ng.has_pose = true;
    ng.region_from_goal = Pose2(goal->point, 0.0);
    ng.position_tolerance = options.position_tolerance;
    ng.heading_tolerance = 3.2;
    const Vector2d goal_world = w.frames.world_from_region.at(goal->region) * goal->point;
    d.planner().set_goal(ng, d.sim().now_utime());
    const double t0 = d.sim().time_s();
    double no_path_at = NAN, reached_at = NAN;
    int no_path_reports = 0;
    auto last = planner::GoalStatus::kNone;
    double next_trace = t0;
    while (d.sim().time_s() - t0 < options.door_case_limit_s) {
      d.step();
      if (options.trace && d.sim().time_s() >= next_trace) {
        next_trace += 1.0;
        trace_line(w.name + " door case gateway " + std::to_string(g->id), d, goal_world);
      }
      const auto st = d.planner().status();
      if (st == planner::GoalStatus::kNoPath && last != st) {
        ++no_path_reports;
        if (std::isnan(no_path_at)) no_path_at = d.sim().time_s() - t0;
      }
      last = st;
      if (st == planner::GoalStatus::kReached) {
        if ((d.truth().translation() - goal_world).norm() <= options.reached_truth_m) reached_at = d.sim().time_s() - t0;
        break;
      }
    }
    const bool reached = !std::isnan(reached_at);
    const int64_t collisions = d.sim().collisions();
    const bool as_expected =
        collisions == 0 && reached &&
        (way_round ? std::isnan(no_path_at) && reached_at < options.door_reopen_s
                   : !std::isnan(no_path_at) && no_path_at < options.door_reopen_s && reached_at > options.door_reopen_s);
    ++s->door_cases;
    s->door_cases_as_expected += as_expected;
    s->door_collisions += collisions;
    s->sim_s += d.sim().time_s();
    s->planner_cpu_s += d.planner_cpu_s();
    nlohmann::json cj = {{"gateway", g->id},
                         {"class", rgmap::to_string(g->cls)},
                         {"regions", {a, b}},
                         {"door_world", {{leaf_world[0].x(), leaf_world[0].y()}, {leaf_world[1].x(), leaf_world[1].y()}}},
                         {"start_world", {start_world.x(), start_world.y()}},
                         {"goal_world", {goal_world.x(), goal_world.y()}},
                         {"way_round_exists", way_round},
                         {"way_round_in_grid_only", way_round_in_grid && !way_round},
                         {"reopens_at_s", options.door_reopen_s},
                         {"no_path_at_s", number_or_null(no_path_at)},
                         {"no_path_reports", no_path_reports},
                         {"reached_at_s", number_or_null(reached_at)},
                         {"replans", d.planner().replans()},
                         {"collisions", collisions},
                         {"as_expected", as_expected},
                         {"planner_reports", d.reasons()}};
    if (!reached) cj["final_world"] = {d.truth().x(), d.truth().y()};
    const auto contacts = d.take_contacts();
    if (!contacts.empty()) cj["contacts"] = contacts;
    if (options.trace) std::cerr << w.name << " door case " << cj.dump() << "\n";
    cases.push_back(cj);
  }
  return cases;
}

}  // namespace

void ClosedLoopSamples::add(const ClosedLoopSamples& o)
{
  goals += o.goals;
  successes += o.successes;
  no_path += o.no_path;
  timeouts += o.timeouts;
  reached_elsewhere += o.reached_elsewhere;
  without_reference += o.without_reference;
  goals_with_no_path_report += o.goals_with_no_path_report;
  goals_out_of_reach += o.goals_out_of_reach;
  collisions += o.collisions;
  replans += o.replans;
  spl.insert(spl.end(), o.spl.begin(), o.spl.end());
  time_s.insert(time_s.end(), o.time_s.begin(), o.time_s.end());
  time_ratio.insert(time_ratio.end(), o.time_ratio.begin(), o.time_ratio.end());
  driven_ratio.insert(driven_ratio.end(), o.driven_ratio.begin(), o.driven_ratio.end());
  sim_s += o.sim_s;
  planner_cpu_s += o.planner_cpu_s;
  door_cases += o.door_cases;
  door_cases_as_expected += o.door_cases_as_expected;
  door_collisions += o.door_collisions;
  contacts.insert(contacts.end(), o.contacts.begin(), o.contacts.end());
}

nlohmann::json ClosedLoopSamples::summary() const
{
  nlohmann::json j;
  j["goals"] = goals;
  j["success_ratio"] = number_or_null(goals ? static_cast<double>(successes) / goals : NAN);
  j["reached"] = successes;
  j["no_path"] = no_path;
  j["goals_with_a_no_path_report"] = goals_with_no_path_report;
  j["timeouts"] = timeouts;
  j["reached_elsewhere"] = reached_elsewhere;
  j["goals_without_reference"] = without_reference;
  j["goals_out_of_reach_skipped"] = goals_out_of_reach;
  j["collisions"] = collisions;
  // What was hit, by kind (the simulator's names without the instance: "table top", "person").
  std::map<std::string, int> kinds;
  for (const auto& c : contacts) {
    std::string k = c;
    const auto dot = k.rfind('.');
    if (dot != std::string::npos && k.find("table") != std::string::npos) k = "table " + k.substr(dot + 1);
    else if (k.rfind("person", 0) == 0) k = "person";
    else if (k.rfind("wall", 0) == 0) k = "wall";
    else if (k.rfind("door", 0) == 0) k = "door";
    ++kinds[k];
  }
  j["collisions_with"] = kinds;
  j["spl"] = number_or_null(mean(spl));
  j["replans"] = replans;
  j["time_s_p50"] = number_or_null(percentile(time_s, 0.5));
  j["time_s_mean"] = number_or_null(mean(time_s));
  j["time_ratio_p50"] = number_or_null(percentile(time_ratio, 0.5));
  j["driven_ratio_p50"] = number_or_null(percentile(driven_ratio, 0.5));
  j["sim_s"] = sim_s;
  j["planner_cpu_share"] = sim_s > 0 ? planner_cpu_s / sim_s : 0.0;
  j["door_cases"] = door_cases;
  j["door_cases_as_expected"] = door_cases_as_expected;
  j["door_case_collisions"] = door_collisions;
  return j;
}

nlohmann::json run_closed_loop(const BenchWorld& w, const ConfigSpace& space, const ClosedLoopSetup& setup,
                               const ClosedLoopOptions& options, std::mt19937_64& rng, ClosedLoopSamples* totals)
{
  ClosedLoopSamples s;
  nlohmann::json goals = run_goals(w, space, setup, options, rng, &s);
  nlohmann::json doors = run_door_cases(w, space, setup, options, rng, &s);
  nlohmann::json j = s.summary();
  j["goal_log"] = goals["goal_log"];
  j["planner_reports"] = goals["planner_reports"];
  j["door_case_log"] = doors;
  totals->add(s);
  return j;
}

}  // namespace rgnav::plan_eval
