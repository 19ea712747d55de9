#include "planner/global_planner.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <set>

#include "geometry/segment2.h"
#include "planner/no_path_reason.h"
#include "rgmap/rg_graph.h"

namespace rgnav::planner {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

GlobalPlanner::GlobalPlanner(const PlannerOptions& options) : options_(options), costs_(options.global) {}

bool GlobalPlanner::is_live(int64_t region) const
{
  const auto* r = map_.region(region);
  return r && r->state != rgmap::Region::State::kMerged;
}

std::vector<NeighbourRegion> GlobalPlanner::neighbours(int64_t region) const
{
  std::vector<NeighbourRegion> out;
  std::set<int64_t> seen{region};
  // Beside it through a gateway: placed by the gateway's transform (what the robot drives by).
  for (const auto& [gid, g] : map_.gateways()) {
    if (g.neutralized || g.region_b == 0) continue;
    const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
    if (a == b || (a != region && b != region)) continue;
    const int64_t other = a == region ? b : a;
    if (!is_live(other) || !seen.insert(other).second) continue;
    out.push_back({map_.region(other), a == region ? g.region_a_from_region_b : g.region_a_from_region_b.inverse()});
  }
  // Overlapping it without a gateway between (a junction's floor split among several regions):
  // placed through the map frame.
  const auto* r = map_.region(region);
  const double margin = options_.grid.neighbour_margin;
  const Eigen::Vector2d lo = r->bbox_min.array() - margin, hi = r->bbox_max.array() + margin;
  const geometry::Pose2 region_from_map = r->map_from_region.inverse();
  for (const auto& [id, other] : map_.regions()) {
    if (!is_live(id) || seen.count(id)) continue;
    const geometry::Pose2 this_from_other = region_from_map * other.map_from_region;
    Eigen::Vector2d olo(1e18, 1e18), ohi(-1e18, -1e18);
    for (const auto& c : {other.bbox_min, Eigen::Vector2d(other.bbox_min.x(), other.bbox_max.y()), other.bbox_max,
                          Eigen::Vector2d(other.bbox_max.x(), other.bbox_min.y())}) {
      olo = olo.cwiseMin(this_from_other * c);
      ohi = ohi.cwiseMax(this_from_other * c);
    }
    if ((olo.array() > hi.array()).any() || (ohi.array() < lo.array()).any()) continue;
    out.push_back({&other, this_from_other});
  }
  return out;
}

int64_t GlobalPlanner::newest_utime(int64_t region) const
{
  int64_t t = map_.region(region)->utime;
  for (const auto& n : neighbours(region)) t = std::max(t, n.region->utime);
  return t;
}

void GlobalPlanner::set_map(const rgmap::RgMap& map)
{
  map_ = map;
  // A region planner stays while neither its region nor a neighbour (it sees their freespace)
  // changed.
  for (auto it = planners_.begin(); it != planners_.end();) {
    if (!is_live(it->first) || newest_utime(it->first) != planner_utime_[it->first]) {
      planner_utime_.erase(it->first);
      it = planners_.erase(it);
    } else {
      ++it;
    }
  }
  paths_.clear();
  // The RG graph (crossing points as nodes), re-indexed for the search.
  rgmap::GraphOptions go;
  go.nominal_speed = options_.global.nominal_speed;
  go.gateway_crossing_time = options_.global.crossing_time;
  const rgmap::RgGraph graph = rgmap::build_graph(map_, go);
  nodes_.clear();
  arcs_.clear();
  nodes_of_region_.clear();
  std::map<int64_t, int> index;
  for (const auto& n : graph.nodes) {
    if (!is_live(n.region_id)) continue;
    index[n.id] = static_cast<int>(nodes_.size());
    nodes_of_region_[n.region_id].push_back(static_cast<int>(nodes_.size()));
    nodes_.push_back({n.region_id, n.gateway_id, n.point, map_.region(n.region_id)->map_from_region * n.point});
  }
  for (const auto& e : graph.edges) {
    const auto a = index.find(e.from), b = index.find(e.to);
    if (a == index.end() || b == index.end()) continue;
    Arc arc;
    arc.from = std::min(a->second, b->second);
    arc.to = std::max(a->second, b->second);
    arc.gateway = e.kind == rgmap::GraphEdge::Kind::kGateway;
    arc.region = arc.gateway ? 0 : e.region_id;
    arc.gateway_id = e.gateway_id;
    arcs_.push_back(arc);
  }
}

const RegionPlanner* GlobalPlanner::region_planner(int64_t region)
{
  region = map_.resolve(region);
  if (!is_live(region)) return nullptr;
  auto& p = planners_[region];
  if (!p) {
    // The region's gateways in its frame.
    std::vector<std::vector<Eigen::Vector2d>> gateways;
    for (const auto& [gid, g] : map_.gateways()) {
      if (g.neutralized) continue;
      const bool is_a = map_.resolve(g.region_a) == region;
      if (!is_a && !(g.region_b && map_.resolve(g.region_b) == region)) continue;
      std::vector<Eigen::Vector2d> points = g.gateway_points;
      if (!is_a)
        for (auto& p : points) p = g.region_a_from_region_b.inverse() * p;
      gateways.push_back(std::move(points));
    }
    std::vector<Eigen::Vector2d> blocked;
    for (const auto& b : places_)
      if (map_.resolve(b.region) == region) blocked.push_back(b.point);
    p = std::make_unique<RegionPlanner>(*map_.region(region), options_.grid, neighbours(region), gateways, blocked);
    planner_utime_[region] = newest_utime(region);
    if (progress_) progress_();
  }
  return p.get();
}

std::optional<Eigen::Vector2d> GlobalPlanner::region_goal_point(int64_t region)
{
  const RegionPlanner* rp = region_planner(region);
  if (!rp) return std::nullopt;
  const RegionGrid& g = rp->grid();
  const Eigen::Vector2d centroid = map_.region(map_.resolve(region))->freespace.features().centroid;
  float best_clear = 0;
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x)
      if (g.free(Cell(x, y))) best_clear = std::max(best_clear, g.clearance(Cell(x, y)));
  if (best_clear <= 0) return std::nullopt;
  // Open space as wide as the comfort zone, or the widest there is, nearest to the centroid.
  const GridOptions& o = options_.grid;
  const double wanted = std::min<double>(best_clear, o.robot_radius + o.clearance_margin + o.comfort_width);
  std::optional<Eigen::Vector2d> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Cell c(x, y);
      if (!g.free(c) || g.clearance(c) < wanted - 1e-6) continue;
      const double d = (g.center_of(c) - centroid).norm();
      if (d < best_d) {
        best_d = d;
        best = g.center_of(c);
      }
    }
  }
  return best;
}

void GlobalPlanner::forget_planner(int64_t region)
{
  planners_.erase(region);
  planner_utime_.erase(region);
  paths_.clear();
}

void GlobalPlanner::block_place(int64_t region, const Eigen::Vector2d& point, double until_s)
{
  region = map_.resolve(region);
  places_.push_back({region, point, until_s});
  forget_planner(region);
}

int64_t GlobalPlanner::region_named(const std::string& name) const
{
  const std::string want = lower(name);
  if (want.empty()) return 0;
  for (const auto& [id, r] : map_.regions())
    if (r.state != rgmap::Region::State::kMerged && lower(r.name) == want) return id;
  return 0;
}

const std::optional<RegionPath>& GlobalPlanner::region_path(const Arc& arc, int from,
                                                            const std::vector<SearchNode>& nodes,
                                                            std::map<PathKey, std::optional<RegionPath>>& cache,
                                                            bool* reversed, PlanStats* stats)
{
  const int a = std::min(arc.from, arc.to), b = std::max(arc.from, arc.to);
  *reversed = from != a;
  const PathKey key{arc.region, a, b};
  auto it = cache.find(key);
  if (it == cache.end()) {
    if (progress_) progress_();
    const auto t0 = std::chrono::steady_clock::now();
    const RegionPlanner* rp = region_planner(arc.region);
    std::optional<RegionPath> path;
    const auto& u = nodes[static_cast<size_t>(a)];
    const auto& v = nodes[static_cast<size_t>(b)];
    // Crossing points reach farther onto the region's free cells than the robot's start or goal.
    const auto reach = [&](const SearchNode& n) {
      if (n.reach > 0) return n.reach;
      return n.gateway ? options_.global.crossing_reach : options_.grid.adapt_distance;
    };
    if (rp && v.robot) {
      // Planned from the robot's place (it may step off a scrap of free space), stored a -> b.
      path = rp->plan(v.point, u.point, nullptr, reach(v), reach(u), u.clear_of_walls, true);
      if (path) std::reverse(path->points.begin(), path->points.end());
    } else if (rp) {
      path = rp->plan(u.point, v.point, nullptr, reach(u), reach(v), v.clear_of_walls, u.robot);
    }
    it = cache.emplace(key, std::move(path)).first;
    if (stats) {
      stats->region_ms += ms_since(t0);
      ++stats->region_paths;
    }
  }
  return it->second;
}

std::optional<std::pair<int64_t, Eigen::Vector2d>> GlobalPlanner::start_beside(int64_t region, const Eigen::Vector2d& p)
{
  // The localizer keeps the robot in a region while it stands on the region's freespace; at a
  // gateway that place may be where the region's grid no longer lets the robot's body stand (the
  // freespace narrows at the opening) while the region beyond has it in its main free space.
  // First the nearest such neighbour within reach of the robot, through the gateway's measured
  // transform.
  const double reach = options_.grid.adapt_distance + options_.grid.robot_radius;
  std::optional<std::pair<int64_t, Eigen::Vector2d>> best;
  double best_d = reach;
  for (const auto& [id, g] : map_.gateways()) {
    if (g.neutralized || g.region_b == 0) continue;
    const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
    if (a == b || (region != a && region != b)) continue;
    const int64_t other = region == a ? b : a;
    if (!is_live(other)) continue;
    const Eigen::Vector2d in_a = region == a ? p : g.region_a_from_region_b * p;
    double d = std::numeric_limits<double>::infinity();
    for (const auto& [u, v] : rgmap::gateway_edges(g.gateway_points))
      d = std::min(d, geometry::point_segment_distance(in_a, u, v));
    if (d > best_d) continue;
    const Eigen::Vector2d there = other == a ? in_a : g.region_a_from_region_b.inverse() * in_a;
    const RegionPlanner* rp = region_planner(other);
    if (!rp || rp->cut_off(there)) continue;
    best_d = d;
    best = std::make_pair(other, there);
  }
  if (best) return best;
  // No gateway near: the robot may have left the region's grid altogether (stepping aside for a
  // person into a doorway, a localizer that hands over late). Any region whose own free space
  // holds the robot's place in the map frame (neighbours are placed consistently there).
  const Eigen::Vector2d in_map = map_.region(region)->map_from_region * p;
  for (const auto& [id, r] : map_.regions()) {
    if (id == region || !is_live(id)) continue;
    const Eigen::Vector2d there = r.map_from_region.inverse() * in_map;
    if (!r.freespace.is_free(there)) continue;
    const RegionPlanner* rp = region_planner(id);
    if (rp && !rp->cut_off(there)) return std::make_pair(id, there);
  }
  return std::nullopt;
}

std::optional<GlobalPlanner::WayBack> GlobalPlanner::back_along_track(int64_t region, const Eigen::Vector2d& p,
                                                                     const std::vector<Eigen::Vector2d>& track)
{
  // Where the robot stands the map may know nothing (collision avoidance took it aside for a
  // person into space the map never saw as free): the places it came by are free, its body was
  // there. The first of them, going back, from which it is not cut off ends the way back; a
  // piece of the track across a line of the map (a localization jump) ends the search.
  const RegionPlanner* rp = region_planner(region);
  if (!rp) return std::nullopt;
  WayBack back;
  back.points.push_back(p);
  for (const Eigen::Vector2d& q : track) {
    const Eigen::Vector2d& prev = back.points.back();
    if (rp->crosses_line(prev, q)) return std::nullopt;
    back.length += (q - prev).norm();
    back.points.push_back(q);
    if (!rp->cut_off(q)) {
      back.region = region;
      back.at = q;
      return back;
    }
    if (const auto beside = start_beside(region, q)) {
      // Ends in the region beside: the way back in its frame, through the map frame (as
      // neighbours are placed consistently there), ending at the place it gave.
      const geometry::Pose2 there_from_here =
          map_.region(beside->first)->map_from_region.inverse() * map_.region(region)->map_from_region;
      for (auto& point : back.points) point = there_from_here * point;
      back.points.back() = beside->second;
      back.region = beside->first;
      back.at = beside->second;
      return back;
    }
  }
  return std::nullopt;
}

std::optional<Route> GlobalPlanner::plan(const PlanRequest& request, std::string* why, PlanStats* stats)
{
  PlanStats local_stats;
  if (!stats) stats = &local_stats;
  *stats = {};
  for (auto it = places_.begin(); it != places_.end();) {
    if (it->until_s > request.now_s) {
      ++it;
      continue;
    }
    forget_planner(map_.resolve(it->region));
    it = places_.erase(it);
  }
  auto route = plan_round_places(request, why, stats);
  if (route || places_.empty()) return route;
  // A blocked place is a reason to go round, not a wall: whoever stood there (people do) may
  // have gone, and the robot was there a moment ago. With no way round, the route goes through
  // it rather than nowhere; refused, a new goal behind a place a person blocked for a few
  // seconds got "no route" from the robot's own region. (The goal held at the place plans with
  // strict_places: round it, or NO_PATH; Planner::handle_stuck. Where the places are all that
  // is in the way, its NO_PATH says so: the same goal can be planned once they are let go, and
  // its sender should not take it for out of reach.)
  const bool tell_blocked = request.strict_places && why && no_path_cause(*why) == NoPathCause::kGoalUnreachable;
  if (request.strict_places && !tell_blocked) return route;
  std::vector<BlockedPlace> kept;
  kept.swap(places_);
  for (const auto& place : kept) forget_planner(place.region);
  PlanStats open_stats;
  route = plan_round_places(request, nullptr, &open_stats);
  places_.swap(kept);
  for (const auto& place : places_) forget_planner(place.region);
  *stats += open_stats;
  if (tell_blocked) {
    if (route) *why = no_path_reason(NoPathCause::kBlockedPlace, why->substr(kGoalUnreachableReason.size()));
    return std::nullopt;
  }
  if (route && why) why->clear();
  return route;
}

std::optional<Route> GlobalPlanner::plan_round_places(const PlanRequest& request, std::string* why, PlanStats* stats)
{
  auto fail = [&](const std::string& text) -> std::optional<Route> {
    if (why) *why = text;
    return std::nullopt;
  };
  int64_t sr = map_.resolve(request.start_region);
  const int64_t gr = map_.resolve(request.goal_region);
  if (!is_live(sr)) return fail("start region " + std::to_string(request.start_region) + " is not in the map");
  if (!is_live(gr))
    return fail(no_path_reason(NoPathCause::kGoalUnreachable, "goal region " + std::to_string(request.goal_region) + " is not in the map"));
  Eigen::Vector2d start_point = request.start;
  std::optional<WayBack> way_back;   // the robot's own track back to where the map has room
  if (region_planner(sr)->cut_off(start_point)) {
    if (const auto beside = start_beside(sr, start_point)) {
      sr = beside->first;
      start_point = beside->second;
    } else if ((way_back = back_along_track(sr, start_point, request.track))) {
      sr = way_back->region;
      start_point = way_back->at;
    }
  }
  // The robot's place may lie in the grids of regions overlapping its own without a gateway
  // between (a junction's or a hall's floor split among several regions). Planned only from its
  // own region, the route may go out through that region's gateway and back in through the
  // other's (to and fro), and the robot, still in its own region on the other's ground, never
  // gets onto the route's next leg. Every region whose grid holds the place is a start of the
  // same search (the cheapest wins; their region paths are planned only where the search goes).
  std::vector<std::pair<int64_t, Eigen::Vector2d>> also;
  if (!way_back) {
    // (A region joined to the start's by a gateway is in the search already, a crossing away.)
    std::set<int64_t> through_gateway{sr};
    for (const auto& [gid, g] : map_.gateways()) {
      if (g.neutralized || g.region_b == 0) continue;
      const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
      if (a == sr) through_gateway.insert(b);
      if (b == sr) through_gateway.insert(a);
    }
    const Eigen::Vector2d in_map = map_.region(sr)->map_from_region * start_point;
    const double margin = options_.grid.neighbour_margin;
    for (const auto& [id, r] : map_.regions()) {
      if (through_gateway.count(id) || !is_live(id)) continue;
      const Eigen::Vector2d there = r.map_from_region.inverse() * in_map;
      if ((there.array() < r.bbox_min.array() - margin).any() || (there.array() > r.bbox_max.array() + margin).any()) continue;
      // Held: a free cell of the region's grid joined to the main piece of its own free space
      // (a grid sees its neighbours' free space too: a region may be mapped thinly where
      // another, overlapping it, was mapped well), with room for the whole body in what the
      // grid knows (not standing partly in its unknown_overlap: that grid knows the place worse).
      const RegionPlanner* rp = region_planner(id);
      if (!rp) continue;
      const RegionGrid& grid = rp->grid();
      const auto cell = grid.nearest_free(grid.cell_of(there), 0.0);
      if (cell && grid.in_main_space(grid.component(*cell)) && grid.clearance(*cell) >= options_.grid.robot_radius)
        also.emplace_back(id, there);
    }
  }
  for (;;) {
    int started = -1;
    auto route = search(request, sr, start_point, also, way_back, why, stats, &started);
    if (!route || started < 0) return route;
    // Begun in another region: that region's grid may hold free cells where the robot's own
    // region has a wall line it does not (each region's grid draws its own lines only). Its
    // first leg must cross no line of the start region's map; else that start is dropped.
    const auto& leg = route->legs.front();
    const geometry::Pose2 here_from_leg =
        map_.region(sr)->map_from_region.inverse() * map_.region(leg.region_id)->map_from_region;
    const RegionPlanner* own = region_planner(sr);
    bool crosses = false;
    for (size_t i = 0; i + 1 < leg.points.size() && !crosses; ++i)
      crosses = own->crosses_line(here_from_leg * leg.points[i], here_from_leg * leg.points[i + 1]);
    if (!crosses) return route;
    also.erase(also.begin() + started);
  }
}

std::optional<Route> GlobalPlanner::search(const PlanRequest& request, int64_t sr, const Eigen::Vector2d& start_point,
                                           const std::vector<std::pair<int64_t, Eigen::Vector2d>>& also,
                                           const std::optional<WayBack>& way_back, std::string* why, PlanStats* stats,
                                           int* started)
{
  auto fail = [&](const std::string& text) -> std::optional<Route> {
    if (why) *why = text;
    return std::nullopt;
  };
  const int64_t gr = map_.resolve(request.goal_region);
  // (A start on no free cell may still step straight to a goal near it: RegionPlanner::plan.)
  const bool a_step = sr == gr && (request.goal - start_point).norm() <= options_.grid.robot_step;
  if (!a_step && !region_planner(gr)->standable(request.goal, request.goal_reach))
    return fail(no_path_reason(NoPathCause::kGoalUnreachable, "the goal is blocked in region " + std::to_string(gr)));

  // Search nodes: the graph's, then the start and the goal, joined to the crossing points of
  // their regions (and to each other in one region).
  std::vector<SearchNode> nodes = nodes_;
  const int start = static_cast<int>(nodes.size()), goal = start + 1;
  nodes.push_back({sr, 0, start_point, map_.region(sr)->map_from_region * start_point, -1, false, true});
  nodes.push_back({gr, 0, request.goal, map_.region(gr)->map_from_region * request.goal, request.goal_reach,
                   request.goal_reach > 0});
  std::vector<Arc> arcs = arcs_;
  auto join = [&](int n, int64_t region) {
    const auto it = nodes_of_region_.find(region);
    if (it == nodes_of_region_.end()) return;
    for (int m : it->second) arcs.push_back({std::min(n, m), std::max(n, m), false, region, 0});
  };
  join(start, sr);
  join(goal, gr);
  if (sr == gr) arcs.push_back({start, goal, false, sr, 0});
  // The same place as a start in the regions overlapping the start's (after the goal: all of
  // them from `start` on are this request's nodes).
  std::vector<int> starts{start};
  for (const auto& [region, point] : also) {
    const int n = static_cast<int>(nodes.size());
    nodes.push_back({region, 0, point, map_.region(region)->map_from_region * point, -1, false, true});
    starts.push_back(n);
    join(n, region);
    if (region == gr) arcs.push_back({goal, n, false, gr, 0});
  }
  std::vector<std::vector<int>> adjacent(nodes.size());
  for (size_t i = 0; i < arcs.size(); ++i) {
    adjacent[static_cast<size_t>(arcs[i].from)].push_back(static_cast<int>(i));
    adjacent[static_cast<size_t>(arcs[i].to)].push_back(static_cast<int>(i));
  }
  // Paths touching the start or goal hold for this request only.
  std::map<PathKey, std::optional<RegionPath>> request_paths;
  auto cache_for = [&](const Arc& a) -> std::map<PathKey, std::optional<RegionPath>>& {
    return std::max(a.from, a.to) >= start ? request_paths : paths_;
  };
  const double speed = options_.global.nominal_speed;
  const double h_speed = std::max(speed, options_.execution.max_speed);
  // The cost of an arc: nullopt when impassable; *exact false while it is the straight-line bound.
  auto arc_cost = [&](const Arc& a, bool* exact) -> std::optional<double> {
    *exact = true;
    if (a.gateway) {
      if (a.gateway_id == request.avoid_gateway) return std::nullopt;
      const auto* g = map_.gateway(a.gateway_id);
      return g ? costs_.gateway_cost(*g, request.now_s, request.closed_hold) : std::nullopt;
    }
    const auto& u = nodes[static_cast<size_t>(a.from)];
    const auto& v = nodes[static_cast<size_t>(a.to)];
    if (costs_.measured(a.region, u.gateway, v.gateway)) return costs_.region_cost(a.region, u.gateway, v.gateway, 0);
    auto& cache = cache_for(a);
    const auto it = cache.find(PathKey{a.region, std::min(a.from, a.to), std::max(a.from, a.to)});
    if (it != cache.end()) {
      if (!it->second) return std::nullopt;
      return it->second->cost / speed;
    }
    *exact = false;
    return (u.point - v.point).norm() / speed;
  };

  std::vector<int> route_arcs;
  double route_cost = 0;
  int first = start;   // the start the route begins at
  for (int iteration = 0;; ++iteration) {
    const auto t0 = std::chrono::steady_clock::now();
    ++stats->searches;
    // A* over the search nodes; the heuristic is the straight distance in the map frame at the
    // fastest speed (a lower bound of every arc's cost).
    std::vector<double> g(nodes.size(), std::numeric_limits<double>::infinity());
    std::vector<int> via(nodes.size(), -1);
    std::vector<char> done(nodes.size(), 0);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    const Eigen::Vector2d goal_map = nodes[static_cast<size_t>(goal)].map_point;
    auto h = [&](int n) { return (nodes[static_cast<size_t>(n)].map_point - goal_map).norm() / h_speed; };
    for (int n : starts) {
      g[static_cast<size_t>(n)] = 0;
      open.push({h(n), n});
    }
    while (!open.empty()) {
      const int u = open.top().second;
      open.pop();
      if (done[static_cast<size_t>(u)]) continue;
      done[static_cast<size_t>(u)] = 1;
      if (u == goal) break;
      for (int ai : adjacent[static_cast<size_t>(u)]) {
        const Arc& a = arcs[static_cast<size_t>(ai)];
        const int v = a.from == u ? a.to : a.from;
        if (done[static_cast<size_t>(v)]) continue;
        bool exact = true;
        const auto c = arc_cost(a, &exact);
        if (!c) continue;
        const double nv = g[static_cast<size_t>(u)] + *c;
        if (nv < g[static_cast<size_t>(v)]) {
          g[static_cast<size_t>(v)] = nv;
          via[static_cast<size_t>(v)] = ai;
          open.push({nv + h(v), v});
        }
      }
    }
    stats->global_ms += ms_since(t0);
    if (!done[static_cast<size_t>(goal)]) {
      std::string closed;
      for (const auto& [gid, gw] : map_.gateways())
        if (costs_.closed(gid, request.now_s)) closed += (closed.empty() ? "" : ", ") + std::to_string(gid);
      std::string route = "no route from region " + std::to_string(sr) + " to region " + std::to_string(gr);
      if (!places_.empty()) route += " (places collision avoidance could not pass: " + std::to_string(places_.size()) + ")";
      // Why, for the goal's sender: the robot's own place joins nothing (standing there, nothing
      // changes: the view must), or only gateways taken for closed for a while are in the way
      // (the same goal once they reopen), or the goal is out of reach from here.
      if (region_planner(sr)->cut_off(start_point))
        return fail(no_path_reason(NoPathCause::kStartCutOff, route + ": the robot stands apart from the region's free space"));
      if (!closed.empty() && request.closed_hold == ClosedHold::kWhole) {
        // A hold beyond closed_retry_s only steers routes round a gateway: with no other way
        // left, one whose last failure is that old is tried again (EdgeCosts).
        PlanRequest retry = request;
        retry.closed_hold = ClosedHold::kBase;
        if (auto again = search(retry, sr, start_point, also, way_back, nullptr, stats, started)) return again;
        PlanRequest open = request;
        open.closed_hold = ClosedHold::kNone;
        if (plan(open, nullptr)) return fail(no_path_reason(NoPathCause::kClosedGateway, route + " (closed gateways: " + closed + ")"));
      }
      return fail(no_path_reason(NoPathCause::kGoalUnreachable, route + (closed.empty() ? "" : " (closed gateways: " + closed + ")")));
    }
    route_arcs.clear();
    for (int n = goal; via[static_cast<size_t>(n)] >= 0;) {
      const int ai = via[static_cast<size_t>(n)];
      route_arcs.push_back(ai);
      const Arc& a = arcs[static_cast<size_t>(ai)];
      n = a.from == n ? a.to : a.from;
      first = n;
    }
    std::reverse(route_arcs.begin(), route_arcs.end());
    route_cost = g[static_cast<size_t>(goal)];
    // Lazy evaluation: plan the region paths the route assumed straight, and search again until
    // the route's every region arc is a planned path (or a measured time).
    bool all_exact = true;
    for (int ai : route_arcs) {
      bool exact = true;
      arc_cost(arcs[static_cast<size_t>(ai)], &exact);
      if (exact) continue;
      all_exact = false;
      bool reversed = false;
      const Arc& a = arcs[static_cast<size_t>(ai)];
      region_path(a, a.from, nodes, cache_for(a), &reversed, stats);
    }
    if (all_exact) break;
  }

  if (started) *started = first == start ? -1 : first - goal - 1;
  // The route: one leg per region on the way, joined by the gateway arcs between them.
  Route route;
  route.map_version = map_.version;
  route.cost_s = route_cost;
  route.goal_heading = request.goal_heading;
  route.has_goal_heading = request.has_goal_heading;
  int at = first;
  int64_t crossed = 0;   // the gateway just crossed (entry of the next leg)
  for (int ai : route_arcs) {
    const Arc& a = arcs[static_cast<size_t>(ai)];
    const int next = a.from == at ? a.to : a.from;
    const auto& u = nodes[static_cast<size_t>(at)];
    const auto& v = nodes[static_cast<size_t>(next)];
    const int from = at;
    at = next;
    if (a.gateway) {
      const auto* gw = map_.gateway(a.gateway_id);
      if (!route.legs.empty()) {
        const bool from_a = map_.resolve(gw->region_a) == u.region;
        route.legs.back().this_from_next = from_a ? gw->region_a_from_region_b : gw->region_a_from_region_b.inverse();
        route.legs.back().exit_gateway = a.gateway_id;
      }
      crossed = a.gateway_id;
      continue;
    }
    bool reversed = false;
    const auto& path = region_path(a, from, nodes, cache_for(a), &reversed, stats);
    std::vector<Eigen::Vector2d> points{u.point, v.point};
    double length = (u.point - v.point).norm(), clearance = 0;
    if (path) {
      points = path->points;
      if (reversed) std::reverse(points.begin(), points.end());
      length = path->length;
      clearance = path->min_clearance;
    }
    route.length += length;
    if (!route.legs.empty() && route.legs.back().region_id == a.region && route.legs.back().exit_gateway == 0) {
      // Through a crossing point without crossing its gateway: the same leg goes on.
      auto& leg = route.legs.back();
      leg.points.insert(leg.points.end(), points.begin() + 1, points.end());
      leg.length += length;
      leg.min_clearance = std::min(leg.min_clearance, clearance);
      continue;
    }
    RouteLeg leg;
    leg.region_id = a.region;
    leg.entry_gateway = crossed;
    leg.points = std::move(points);
    leg.length = length;
    leg.min_clearance = clearance;
    route.legs.push_back(std::move(leg));
    crossed = 0;
  }
  if (way_back && first == start && !route.legs.empty() && route.legs.front().region_id == sr) {
    // The route begins with the way back: the first leg starts where the robot stands.
    RouteLeg& first = route.legs.front();
    std::vector<Eigen::Vector2d> points = way_back->points;
    points.insert(points.end(), first.points.begin() + 1, first.points.end());
    first.points = std::move(points);
    first.length += way_back->length;
    // (min_clearance stays the planned part's: along the track the map knows nothing to measure.)
    route.length += way_back->length;
    route.cost_s += way_back->length / speed;
  }
  smooth_crossings(&route);
  if (why) why->clear();
  return route;
}

void GlobalPlanner::smooth_crossings(Route* route)
{
  // A route passes each gateway at its crossing point; across a wide opening (a hallway's
  // crossing) the straight line from the point before it to the point after it is shorter.
  // The crossing moves to where that line passes nearest the crossing point, if the line is
  // free and no dearer on both sides (each side checked in its own region's grid).
  for (size_t k = 0; k + 1 < route->legs.size(); ++k) {
    RouteLeg& a = route->legs[k];
    RouteLeg& b = route->legs[k + 1];
    if (a.points.size() < 2 || b.points.size() < 2) continue;
    const RegionPlanner* pa = region_planner(a.region_id);
    const RegionPlanner* pb = region_planner(b.region_id);
    if (!pa || !pb) continue;
    const geometry::Pose2 a_from_b = a.this_from_next;
    const Eigen::Vector2d before = a.points[a.points.size() - 2], cross = a.points.back();
    const Eigen::Vector2d after = a_from_b * b.points[1];
    const Eigen::Vector2d d = after - before;
    if (d.norm() < 1e-6) continue;
    const double t = std::clamp((cross - before).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d moved = before + t * d;
    if ((moved - cross).norm() < pa->grid().resolution()) continue;
    const geometry::Pose2 b_from_a = a_from_b.inverse();
    const auto new_a = pa->grid().line_cost(before, moved);
    const auto new_b = pb->grid().line_cost(b_from_a * moved, b.points[1]);
    const auto old_a = pa->grid().line_cost(before, cross);
    const auto old_b = pb->grid().line_cost(b.points[0], b.points[1]);
    if (!new_a || !new_b) continue;
    // The old pieces may reach into what a region does not know (an adapted crossing point):
    // then any free straight line is better.
    if (old_a && old_b && *new_a + *new_b > *old_a + *old_b + 1e-6) continue;
    const double a_change = (moved - before).norm() - (cross - before).norm();
    const double b_change = (after - moved).norm() - (b.points[1] - b.points[0]).norm();
    a.points.back() = moved;
    b.points.front() = b_from_a * moved;
    a.length += a_change;
    b.length += b_change;
    route->length += a_change + b_change;
  }
}

}  // namespace rgnav::planner
