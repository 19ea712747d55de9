// The explorer benchmark's baseline: frontier-based exploration as Yamauchi (1997) describes it and
// explore_lite does it. One whole-building occupancy grid in the map frame, built from the accepted
// scans at the scan mapper's poses (log-odds: hits raise a cell, beams through it lower it; the
// robot's footprint is free); frontiers are free cells with an unknown 4-neighbour, clustered
// 8-connected, a cluster at least the robot's width; the goal is the frontier cell nearest to the
// robot by a breadth-first search over free cells where the robot fits; the path to it is grid A*
// with a wall cost (plan_eval::GridSearch) on the grid with unknown cells taken as free (as NavFn
// with allow_unknown), re-planned every period from where the robot is, cut into targets for
// collision avoidance. A goal the robot has reached without the frontier going, or makes no
// progress toward for progress_timeout_s (explore_lite's), is blacklisted. It ends when no
// frontier is left that it can reach.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/pose2.h"
#include "occupancy_grid.h"
#include "sensors/laser_scan.h"

namespace rgnav::explore_eval {

using plan_eval::Cell;

struct FrontierOptions
{
  double resolution = 0.1;         // [m]
  double half_extent = 100.0;      // [m] the grid covers +- this around the map origin
  double max_range = 8.0;          // [m] beams end here (no return: free up to here)
  double robot_radius = 0.26;      // [m]
  double min_frontier_m = 0.52;    // [m] a cluster of fewer cells than this / resolution is no goal (robot width)
  double period_s = 1.0;           // [s] decisions and re-planning
  double target_spacing = 1.5;     // [m] largest gap between targets
  double straight_clearance = 0.15;  // [m] beyond the radius: the path is straightened where this much is left
  double fit_margin = 0.05;        // [m] the search for the nearest frontier goes where clearance >= radius + this
  double goal_reached_m = 0.8;     // [m] the laser sees past a frontier this near
  double stuck_near_goal_s = 5.0;  // [s] collision avoidance cannot get nearer than stuck_distance_m this long: blacklisted
  double stuck_distance_m = 1.5;   // [m]
  double progress_timeout_s = 30.0;  // [s]
  double progress_m = 0.3;         // [m] nearer to the goal by this counts as progress
  double blacklist_radius = 0.6;   // [m] frontier cells this near a blacklisted goal are no goals
};

// A log-odds occupancy grid in the map frame.
class ScanGrid
{
 public:
  ScanGrid(double resolution, double half_extent);

  void add_scan(const geometry::Pose2& map_from_base, const geometry::Pose2& base_from_laser, const sensors::LaserScan& scan,
                double max_range, double robot_radius);
  // kUnknown / kFree / kOccupied (plan_eval::OccupancyGrid's values).
  uint8_t state(const Cell& c) const;
  const plan_eval::OccupancyGrid& geometry() const { return geometry_; }   // extent only; cells unused
  // Cells touched so far: [min, max] corners (empty: max < min).
  Cell touched_min() const { return min_; }
  Cell touched_max() const { return max_; }
  // The grid cropped to the touched cells + `margin` cells, unknown cells as `unknown_as`, the
  // outermost ring unknown.
  plan_eval::OccupancyGrid cropped(int margin, uint8_t unknown_as) const;

 private:
  void touch(const Cell& c);
  plan_eval::OccupancyGrid geometry_;
  std::vector<int8_t> log_odds_;
  std::vector<uint8_t> touched_;
  Cell min_{1, 1}, max_{0, 0};
};

struct FrontierCluster
{
  std::vector<Cell> cells;
  Eigen::Vector2d centroid{0, 0};   // map frame
};

// Frontier clusters of `grid` (free cells with an unknown 4-neighbour, 8-connected) of at least
// min_cells cells.
std::vector<FrontierCluster> find_frontier_clusters(const plan_eval::OccupancyGrid& grid, int min_cells);

class FrontierExplorer
{
 public:
  explicit FrontierExplorer(const FrontierOptions& options);
  ~FrontierExplorer();

  void add_scan(const geometry::Pose2& map_from_base, const geometry::Pose2& base_from_laser, const sensors::LaserScan& scan);

  struct Decision
  {
    bool new_targets = false;
    std::vector<geometry::Pose2> map_targets;   // map frame, driving order
    int64_t goal_id = 0;
  };
  // Every period: the goal and the path from the robot (map frame) to it.
  // `cannot_pass`: collision avoidance stands without a way to the targets.
  Decision step(double t_s, const geometry::Pose2& map_from_base, bool cannot_pass);
  bool done() const { return done_; }
  const std::string& activity() const { return activity_; }
  int goals() const { return goals_; }
  int blacklisted() const { return static_cast<int>(blacklist_.size()); }
  int no_path() const { return no_path_; }
  double cpu_s() const { return cpu_s_; }
  const ScanGrid& grid() const { return grid_; }

 private:
  struct Space;
  FrontierOptions options_;
  ScanGrid grid_;
  std::unique_ptr<Space> space_;
  double last_step_s_ = -1e9;
  bool done_ = false;
  int scans_ = 0;
  std::optional<Eigen::Vector2d> goal_;
  int64_t goal_id_ = 0;
  double best_distance_ = 0, progress_s_ = 0;
  double passable_since_s_ = 0;    // collision avoidance could pass since then
  std::vector<Eigen::Vector2d> blacklist_;
  int goals_ = 0, no_path_ = 0;
  double cpu_s_ = 0;
  std::string activity_ = "waiting for scans";
};

}  // namespace rgnav::explore_eval
