// Searches on a whole-building configuration space (occupancy_grid.h), the planning benchmark's
// yardsticks for rgnav's routes:
//   - the reference, "the exact shortest path on the same occupancy": 16-connected A* (the 8
//     neighbours and the 8 knight moves) with Euclidean step lengths, then any-angle smoothing by
//     string pulling with line of sight on the configuration space (from each end, the shorter
//     kept), its turns then cut as far as the line of sight allows: the shortest collision-free
//     length up to the grid's resolution;
//   - the baseline, "whole-building grid A*" as NavFn-style planners do it: 8-connected A* on the
//     same grid with a wall cost like rgnav's (cost per metre rising toward the walls over a
//     comfort band beyond the robot radius), no smoothing.
// Start and goal on a cell the robot's centre may not occupy are moved to the nearest free cell
// within adapt_distance from which the other end can be reached, as rgnav's region planner moves
// them onto its region's own space.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "occupancy_grid.h"

namespace rgnav::plan_eval {

struct GridPath
{
  std::vector<Eigen::Vector2d> points;   // map frame, start to goal (adapted ends)
  double length = 0;                     // [m]
  double cost = 0;                       // [m] weighted by the wall cost (baseline); = length for the reference
  int expanded = 0;                      // cells taken off the open list
};

// The baseline's wall cost, rgnav's region grid's without its quantisation: per metre 1 in open
// space, 1 + comfort_cost in the comfort band [radius + margin, radius + margin + comfort), and
// inside the margin rising linearly to 1 + wall_cost at the radius.
struct WallCost
{
  double margin = 0.15;       // [m]
  double comfort = 0.25;      // [m]
  double wall_cost = 3.0;
  double comfort_cost = 0.1;
  double factor(double clearance, double radius) const;
};

class Components
{
 public:
  Components(const ConfigSpace& space, double min_clearance);
  // Component of cell c; -1 when its clearance is below the threshold.
  int32_t label(const Cell& c) const;
  // The cell of the set nearest to c no farther than max_distance [m].
  std::optional<Cell> nearest(const Cell& c, double max_distance) const;
  // Both points have a cell of the set within max_distance, and those are joined.
  bool joined(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double max_distance) const;

 private:
  const ConfigSpace& space_;
  double min_clearance_;
  std::vector<int32_t> label_;
};

class GridSearch
{
 public:
  explicit GridSearch(const ConfigSpace& space);

  // The reference shortest path; nullopt when start or goal cannot be placed or no path exists.
  std::optional<GridPath> shortest(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double adapt_distance);
  // The baseline; nullopt as above. Without `heuristic` the search is Dijkstra's, as NavFn
  // propagates its potential.
  std::optional<GridPath> wall_cost_astar(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double adapt_distance,
                                          const WallCost& cost, bool heuristic = true);
  // Whether any path exists between the two (connected components, labelled once).
  bool connected(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double adapt_distance);

  const ConfigSpace& space() const { return space_; }

 private:
  // A* from start to goal cell over `moves` neighbours; per-cell cost factor from `weight`
  // (nullptr: 1). Returns the cell path.
  std::optional<std::vector<Cell>> astar(const Cell& start, const Cell& goal, bool sixteen, const std::vector<float>* weight,
                                         int* expanded, bool heuristic = true);
  std::vector<Eigen::Vector2d> pull_string(const std::vector<Eigen::Vector2d>& points) const;
  std::vector<Eigen::Vector2d> tighten(std::vector<Eigen::Vector2d> points) const;
  // Start and goal cells: free, within adapt_distance of the points, joined.
  std::optional<std::pair<Cell, Cell>> adapted_ends(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double adapt_distance);

  const ConfigSpace& space_;
  // Search buffers reused between queries (stamped by query, never cleared).
  std::vector<float> g_;
  std::vector<int32_t> parent_;
  std::vector<uint32_t> stamp_;
  std::vector<uint32_t> closed_;
  uint32_t query_ = 0;
  std::optional<Components> components_;   // of the free cells (lazy)
  std::vector<float> wall_weight_;       // the baseline's per-cell cost factor (lazy)
  WallCost wall_weight_for_;
};

}  // namespace rgnav::plan_eval
