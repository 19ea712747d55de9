// Global planning on the RG graph (diss. 2.1.3, 5.4): A* over the crossing points of the map's
// gateways, with the robot's start and the goal as extra nodes joined to the crossing points of
// their regions. A region edge costs its straight length over the nominal speed until its
// region path is planned (a lower bound), then that path's length, then the measured time once
// driven; the search is repeated with the planned lengths of the edges it chose until its route
// uses only planned or measured edges (lazy evaluation: few region paths are planned, and the
// route is the cheapest by real path lengths). Gateway edges cost what EdgeCosts says; closed
// ones are left out. The region planners are built on first use and kept per region version.
//
// Where the route starts (the robot's place need not be where its region's grid has room):
//   rule                                   | failure it fixes                          | test
//   pose region's free space, else the     | at a gateway the pose's region has no room | Planner.StartsWhereTheRobotStands...
//   region beside (start_beside)           | for the body, the neighbour has            |
//   else back along the robot's own track  | yielding took it into space no region knows:| GlobalPlanner.ARobotCutOffGoesBack...,
//   (back_along_track, never across a line)| "start cut off" for every later goal        | Planner.ARobotCutOffIsRoutedBack...
//   the cheapest of every region whose     | overlapping regions without a gateway: out | GlobalPlanner.AStartInOverlapping...
//   grid holds the place in its main piece | one's gateway and back in (to and fro)     |
//   (no gateway joins it to the start's),  |                                            |
//   its first leg across no line of the    | a thin region's grid free where the robot's| GlobalPlanner.AStartInOverlapping...
//   robot's own region                     | own region has a wall                      |
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "planner/edge_costs.h"
#include "planner/planner_options.h"
#include "planner/region_planner.h"
#include "planner/route.h"
#include "rgmap/rg_map.h"

namespace rgnav::planner {

struct PlanRequest
{
  int64_t start_region = 0;
  Eigen::Vector2d start{0, 0};     // start region frame
  int64_t goal_region = 0;
  Eigen::Vector2d goal{0, 0};      // goal region frame
  double goal_heading = 0;         // [rad] goal region frame
  bool has_goal_heading = false;
  // The goal may lie this far [m] from the region's free cells (> 0; else GridOptions::
  // adapt_distance), in unknown space reached straight from the nearest free cell through no
  // line of the region's map (NavGoal::beyond_known).
  double goal_reach = -1;
  double now_s = 0;                // message time, for closed gateways
  int64_t avoid_gateway = 0;       // a gateway not to cross (is there a way round it?)
  // Gateways found closed: left out for their whole hold; where that leaves no route, one
  // closed_retry_s past its last failure is planned through (the search's own retry, kBase);
  // kNone: as if none were closed (is a closed one all that is in the way?).
  ClosedHold closed_hold = ClosedHold::kWhole;
  // Blocked places (block_place) as walls: no route through one even when there is no other (is
  // there a way round?). Otherwise a route goes round them where it can, through them where not.
  bool strict_places = false;
  // The robot's own recent places, start region frame, newest first (Planner keeps them): its
  // body was there, so they are free whatever the map says. A start cut off from the region's
  // free space (yielding to a person into space the map never saw) goes back along them to the
  // first place that is not cut off; never across a line of the map.
  std::vector<Eigen::Vector2d> track{};
};

struct PlanStats
{
  double global_ms = 0;            // graph searches
  double region_ms = 0;            // region paths planned for this request
  int searches = 0;                // A* runs until the route was exact
  int region_paths = 0;            // region paths planned (cache misses)
  PlanStats& operator+=(const PlanStats& o)
  {
    global_ms += o.global_ms;
    region_ms += o.region_ms;
    searches += o.searches;
    region_paths += o.region_paths;
    return *this;
  }
};

class GlobalPlanner
{
 public:
  explicit GlobalPlanner(const PlannerOptions& options);

  // A new map (version): regions whose description changed get new region planners.
  void set_map(const rgmap::RgMap& map);
  const rgmap::RgMap& map() const { return map_; }
  EdgeCosts& costs() { return costs_; }
  const EdgeCosts& costs() const { return costs_; }

  // The cheapest route; nullopt with *why set when there is none, beginning with its cause
  // (no_path_reason.h: "start cut off: ...", "goal unreachable: ...", "behind a closed gateway: ...",
  // "behind a blocked place: ...").
  std::optional<Route> plan(const PlanRequest& request, std::string* why, PlanStats* stats = nullptr);

  // The region planner of a live region (built on first use); nullptr for an unknown region.
  const RegionPlanner* region_planner(int64_t region);
  // Called after each region planner built and each path searched within a region: a plan on a
  // large map takes seconds on a loaded host, during which a process shows that it is alive.
  void set_progress(std::function<void()> progress) { progress_ = std::move(progress); }
  // The robot at p in `region` cut off from its free space there, but standing in the main free
  // space of a neighbour across a gateway within reach: that region and p in its frame.
  std::optional<std::pair<int64_t, Eigen::Vector2d>> start_beside(int64_t region, const Eigen::Vector2d& p);
  // The robot at p in `region` cut off (and no start_beside): back along its `track` (region
  // frame, newest first) to the first place from which it is not, in `region` or beside it.
  struct WayBack
  {
    int64_t region = 0;                  // where the way back ends ...
    Eigen::Vector2d at{0, 0};            // ... and the place there, in its frame
    std::vector<Eigen::Vector2d> points; // p, then the track's places up to `at`, in `region`'s frame
    double length = 0;                   // [m]
  };
  std::optional<WayBack> back_along_track(int64_t region, const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& track);
  // A place to send the robot in a region given by name only: the free cell of its grid with
  // the largest clearance nearest to its freespace centroid. nullopt for a region with no free cell.
  std::optional<Eigen::Vector2d> region_goal_point(int64_t region);
  // The live region named `name` (case-insensitive), 0 if none.
  int64_t region_named(const std::string& name) const;
  // Collision avoidance could not pass at `point` (region frame) where the grid sees a way (what
  // the line map holds too thinly, people standing): an obstacle there until until_s (message
  // time), routes planned round it where there is a way round (through it where there is none,
  // unless PlanRequest::strict_places). Places past their time are dropped at the next plan().
  void block_place(int64_t region, const Eigen::Vector2d& point, double until_s);
  size_t blocked_places() const { return places_.size(); }

 private:
  // plan() with the blocked places as they are (walls).
  std::optional<Route> plan_round_places(const PlanRequest& request, std::string* why, PlanStats* stats);
  // The cheapest route from the robot at start_point in region sr (its way back along the track
  // first, if any), or from the same place in the regions `also` (region, place in its frame),
  // to the request's goal; stats added to; *started: the index in `also` the route begins at (-1:
  // the robot's own region).
  std::optional<Route> search(const PlanRequest& request, int64_t sr, const Eigen::Vector2d& start_point,
                              const std::vector<std::pair<int64_t, Eigen::Vector2d>>& also,
                              const std::optional<WayBack>& way_back, std::string* why, PlanStats* stats,
                              int* started = nullptr);
  // A traversal the search may take: through a region between two points (graph nodes, or the
  // request's start / goal), or across a gateway.
  struct Arc
  {
    int from = 0, to = 0;          // search node indices (graph nodes, then start, then goal)
    bool gateway = false;
    int64_t region = 0;            // region arcs
    int64_t gateway_id = 0;        // gateway arcs
  };
  struct SearchNode
  {
    int64_t region = 0;
    int64_t gateway = 0;           // 0: the start or goal
    Eigen::Vector2d point{0, 0};   // region frame
    Eigen::Vector2d map_point{0, 0};
    double reach = -1;             // [m] onto the region's free cells (< 0: by kind, see region_path)
    bool clear_of_walls = false;   // a goal past the freespace: reached through no wall
    bool robot = false;            // the robot's start: its body stands there (RegionPlanner::plan's from_is_robot)
  };
  using PathKey = std::tuple<int64_t, int, int>;   // region, from node, to node (from < to)

  // The region path of a region arc, planned once (nullopt: no way); `reversed` when it is
  // stored the other way than driven from node `from`.
  const std::optional<RegionPath>& region_path(const Arc& arc, int from, const std::vector<SearchNode>& nodes,
                                               std::map<PathKey, std::optional<RegionPath>>& cache, bool* reversed,
                                               PlanStats* stats);
  bool is_live(int64_t region) const;
  // Moves each gateway crossing of the route onto the straight line past it where that is free
  // and no dearer (wide openings are not crossed at one fixed point).
  void smooth_crossings(Route* route);
  // The live regions beside `region` through a gateway, placed in its frame.
  std::vector<NeighbourRegion> neighbours(int64_t region) const;
  // The newest change of the region or a neighbour (a region planner is rebuilt when it moves).
  int64_t newest_utime(int64_t region) const;

  PlannerOptions options_;
  rgmap::RgMap map_;
  EdgeCosts costs_;
  std::vector<SearchNode> nodes_;                                    // graph nodes of this map version
  std::vector<Arc> arcs_;                                            // between graph nodes
  std::map<int64_t, std::vector<int>> nodes_of_region_;
  std::map<int64_t, std::unique_ptr<RegionPlanner>> planners_;      // per live region
  std::function<void()> progress_;                                   // set_progress
  std::map<int64_t, int64_t> planner_utime_;                         // region utime they were built from
  std::map<PathKey, std::optional<RegionPath>> paths_;               // between graph nodes, this map version
  struct BlockedPlace { int64_t region; Eigen::Vector2d point; double until_s; };
  std::vector<BlockedPlace> places_;
  // Rebuilds the region planner of `region` (its blocked places changed).
  void forget_planner(int64_t region);
};

}  // namespace rgnav::planner
