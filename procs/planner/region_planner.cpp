#include "planner/region_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/segment2.h"

namespace rgnav::planner {

namespace {

constexpr int kMaxQuadCells = 32;

}  // namespace

RegionPlanner::RegionPlanner(const rgmap::Region& region, const GridOptions& options,
                             const std::vector<NeighbourRegion>& neighbours,
                             const std::vector<std::vector<Eigen::Vector2d>>& gateways,
                             const std::vector<Eigen::Vector2d>& blocked)
    : grid_options_(options), grid_(region, options, neighbours, gateways, blocked), tree_(grid_, kMaxQuadCells)
{
  for (const auto& s : region.segments) walls_.emplace_back(s.a, s.b);
}

bool RegionPlanner::standable(const Eigen::Vector2d& p, double reach) const
{
  return grid_.nearest_free(grid_.cell_of(p), reach).has_value();
}

bool RegionPlanner::cut_off(const Eigen::Vector2d& p, double reach) const
{
  const double r = reach < 0 ? grid_options_.adapt_distance : reach;
  const auto c = grid_.nearest_free(grid_.cell_of(p), r);
  if (c && grid_.in_main_space(grid_.component(*c))) return false;
  return !grid_.nearest_reachable_in(p, grid_.main_component(), r).has_value();
}

bool RegionPlanner::crosses_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const
{
  for (const auto& [u, v] : walls_)
    if (geometry::segments_cross(a, b, u, v)) return true;
  return false;
}

std::optional<RegionPath> RegionPlanner::plan(const Eigen::Vector2d& from, const Eigen::Vector2d& to, std::string* why,
                                              double from_reach, double to_reach, bool to_clear_of_walls,
                                              bool from_is_robot) const
{
  auto fail = [&](const char* text) -> std::optional<RegionPath> {
    if (why) *why = text;
    return std::nullopt;
  };
  auto start = grid_.nearest_free(grid_.cell_of(from), from_reach);
  const auto goal = grid_.nearest_free(grid_.cell_of(to), to_reach);
  if (from_is_robot && goal && (!start || grid_.component(*start) != grid_.component(*goal))) {
    // The nearest free cell is a scrap apart from the goal's space: the robot steps straight
    // into that space where it can.
    const double reach = from_reach < 0 ? grid_options_.adapt_distance : from_reach;
    if (const auto joined = grid_.nearest_reachable_in(from, grid_.component(*goal), reach)) start = joined;
  }
  if (from_is_robot && (!start || !goal || grid_.component(*start) != grid_.component(*goal)) &&
      (to - from).norm() <= grid_options_.robot_step && grid_.clear_of_lines(from, to)) {
    // Cut off from the goal's space, but the goal a step away with nothing of the map between:
    // straight there (a step back to where the body just was; collision avoidance sees the rest).
    RegionPath step;
    step.points = {from, to};
    step.length = (to - from).norm();
    step.cost = step.length * grid_.max_level_cost();
    step.min_clearance = grid_.line_clearance(from, to);
    if (why) why->clear();
    return step;
  }
  if (!start) return fail("start is blocked");
  if (!goal) return fail("goal is blocked");
  if (to_clear_of_walls && *goal != grid_.cell_of(to)) {
    const Eigen::Vector2d g = grid_.center_of(*goal);
    if (crosses_line(g, to)) return fail("goal is behind a wall");
  }
  QuadSearchStats stats;
  const auto cells = tree_.search(*start, *goal, &stats);
  if (!cells) return fail("no way inside the region");

  // Start and goal adaption (diss. 5.4): the search ran between cell centres; the path begins
  // and ends at the requested points, through the adapted free cells when those were blocked
  // (a crossing point on a door line lies at the edge of the region's known freespace; one in
  // the middle of a crossing's square may lie outside the freespace of the region beside it).
  std::vector<Eigen::Vector2d> inner;
  inner.reserve(cells->size());
  for (const Cell& c : *cells) inner.push_back(grid_.center_of(c));
  const bool start_free = *start == grid_.cell_of(from);
  const bool goal_free = *goal == grid_.cell_of(to);
  if (start_free) inner.front() = from;
  if (goal_free) inner.back() = to;
  inner = smooth(inner);

  RegionPath path;
  if (!start_free) path.points.push_back(from);
  path.points.insert(path.points.end(), inner.begin(), inner.end());
  if (!goal_free) path.points.push_back(to);
  path.min_clearance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < path.points.size(); ++i) {
    const auto& a = path.points[i];
    const auto& b = path.points[i + 1];
    const double len = (b - a).norm();
    path.length += len;
    const auto c = grid_.line_cost(a, b);
    path.cost += c ? *c : len * grid_.max_level_cost();
    // The adapted ends reach into what the region does not know (past a door line): their
    // clearance says nothing about walls.
    const bool adapted_end = (i == 0 && !start_free) || (i + 2 == path.points.size() && !goal_free);
    if (!adapted_end) path.min_clearance = std::min(path.min_clearance, grid_.line_clearance(a, b));
  }
  if (path.points.size() < 2 || !std::isfinite(path.min_clearance)) {
    path.min_clearance = grid_.clearance(*start);
  }
  path.expanded = stats.expanded;
  if (why) why->clear();
  return path;
}

std::vector<Eigen::Vector2d> RegionPlanner::smooth(const std::vector<Eigen::Vector2d>& points) const
{
  if (points.size() <= 2) return points;
  // Cost of each piece of the found path, and of the path up to each point.
  std::vector<double> upto(points.size(), 0.0);
  for (size_t i = 1; i < points.size(); ++i) {
    const auto c = grid_.line_cost(points[i - 1], points[i]);
    upto[i] = upto[i - 1] + (c ? *c : (points[i] - points[i - 1]).norm() * grid_.level_cost(0));
  }
  // Greedy shortcuts: from each kept point, the farthest later point reachable on a free
  // straight line that costs no more than the way through the points between.
  std::vector<Eigen::Vector2d> out{points.front()};
  size_t i = 0;
  while (i + 1 < points.size()) {
    size_t next = i + 1;
    for (size_t j = points.size() - 1; j > i + 1; --j) {
      const auto c = grid_.line_cost(points[i], points[j]);
      if (c && *c <= upto[j] - upto[i] + 1e-6) {
        next = j;
        break;
      }
    }
    out.push_back(points[next]);
    i = next;
  }
  return out;
}

}  // namespace rgnav::planner
