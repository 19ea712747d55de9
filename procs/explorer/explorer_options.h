// Parameters of the explorer (diss. 5.0 high-level planning, ch. 7 region-by-region exploration
// with a gateway stack), as config/explorer.yaml names them. Defaults are the values documented
// there.
#pragma once

#include <string>

#include "planner/planner_options.h"

namespace rgnav::config { class Config; struct RobotDescription; }

namespace rgnav::explorer {

// What a look past a frontier can still show (view_gain.h): the unknown area in a fan of rays.
struct GainOptions
{
  double range_m = 2.0;            // [m] rays this long (a look from the view point sees farther: this is what a frontier
                                   // must at least offer near it)
  double fan_rad = 1.0;            // [rad] rays this far to either side of the frontier's outward direction
  double step_m = 0.1;             // [m] samples along a ray, and rays this far apart at the fan's rim
  double min_m2 = 0.0;             // [m^2] a frontier with less unknown area than this in its fan is no goal (0: every one)
  // [m^2] the same for the frontiers of a region the robot is not in (when larger): going back
  // costs a trip, and a region the robot saw from inside keeps scraps of freespace edge its map
  // does not close (corners, furniture) that a look from there has already seen past
  double left_min_m2 = 0.0;
};

// Where a region's freespace ends in unknown space (frontiers.h).
struct FrontierOptions
{
  double wall_distance = 0.3;      // [m] a line of the region's map this far past a freespace edge, across the way out, is
                                   // the wall that ends the freespace there (not a frontier)
  double min_width = 0.6;          // [m] a frontier narrower than this is a shadow (behind a table leg, a corner)
  double gateway_distance = 0.8;   // [m] a freespace edge this near a traversed door's line is its opening
  GainOptions gain;                // a frontier offering less unknown area than gain.min_m2 is no goal (the explorer's rule)
};

// Untraversed gateways (gateway_stack.h): the gateway detector's sightings, kept in the map frame.
struct StackOptions
{
  int min_observations = 3;        // a sighting tracked over fewer scans is not stacked
  double merge_distance = 1.0;     // [m] a sighting this near a stacked entry, heading within merge_angle, is that entry
  double merge_angle = 0.8;        // [rad]
  double beyond_m = 1.0;           // [m] the goal lies this far past the gateway's crossing point
  double passed_m = 0.4;           // [m] the robot this far past a door's crossing point (a crossing's goal) has gone through
  bool breadth_first = true;       // order: fewest RG-graph hops from the start region first (else nearest first)
  // Every region of the map complete before a new gateway (diss. ch. 7): the frontiers of regions
  // entered before come ahead of the stack (else only the current region's come first, and a region
  // the robot stepped out of for a moment waits until the stack is empty). A frontier that failed
  // once, the current region's too, comes after the stack either way.
  bool after_regions = true;
  // A goal through an entry is aimed through the opening the map's lines show beside its crossing
  // point (opening.h), looked for this far to either side (0: the crossing point as seen).
  double aim_search_m = 1.0;
};

// Where the robot looks at a frontier from (view_point.h): a place the planner's grid has room for
// and a way to, within range of the frontier and in sight of it.
struct ViewOptions
{
  double range_m = 1.5;            // [m] the view point lies at most this far from the frontier (the laser sees 8 m: near
                                   // enough to look past the frontier's edge into what lies beyond it)
  double clearance_weight = 2.0;   // a metre of clearance short of radius + margin counts as this many metres farther
  double heading_tolerance = 1.2;  // [rad] the robot faces the frontier this nearly (the laser's field is +-90 deg)
};

// When the planner says the robot's own place joins nothing (its region grid has the robot in a
// scrap of free space: clutter, ragged freespace, unknown space behind it, the laser seeing only
// ahead), standing there changes nothing: the robot changes its view. It turns on the spot to
// face away from where it looks (the laser sees the half behind it), and if that does not do,
// steps back along its own track (where its body was: free) and tries again.
struct RecoveryOptions
{
  bool look_at_start = true;       // the first thing: a look behind (a map of what lies ahead only cuts the start off)
  double heading_tolerance = 0.35; // [rad] the turn is done this near the heading behind
  double step_m = 0.8;             // [m] the step back goes to the place on the track this far away
  double timeout_s = 30.0;         // [s] a look or a step not done in this long has failed
};

// A goal set aside for good is tried again once the map near it changed by this much (place_view.h).
struct PlaceViewOptions
{
  double radius_m = 2.0;           // [m] the neighbourhood of the place
  double sample_m = 0.1;           // [m] free space is sampled on a lattice this fine
  double changed_area_m2 = 0.1;    // [m^2] free area gained or lost that counts as a change
  double changed_wall_m = 0.15;    // [m] wall length gained or lost that counts as a change
};

struct ExplorerOptions
{
  FrontierOptions frontier;
  StackOptions stack;
  RecoveryOptions recovery;
  ViewOptions view;
  PlaceViewOptions changed;
  // The planner's grid (its config's grid section): view points are cells the planner can reach.
  planner::GridOptions grid;
  double robot_radius = 0.26;      // [m] from the robot description
  double goal_tolerance = 0.5;     // [m] NAV_GOAL position tolerance of a frontier goal
  double gateway_goal_tolerance = 0.4;  // [m] ... of a goal beyond a gateway
  double visited_radius = 1.0;     // [m] a frontier whose goal the robot reached is not a goal again within this
  double retry_after_s = 60.0;     // [s] a goal the planner found no path for is tried again after this (and
                                   // whenever the map gained a region since)
  int max_attempts = 3;            // ... at most this many times (a failure counts only if the robot moved or the map
                                   // changed since the last one); then it is set aside for good (with its reason) until
                                   // the map near it changes (`changed`), at least retry_after_s after its last failure
  // A goal only a gateway the planner holds closed is in the way of: no attempt of its own (the
  // door may open), tried again after retry_after_s, twice as long after each such failure, and
  // after this many set aside for good like one out of attempts (a door shut for good would
  // otherwise be tried every minute, and exploring would never end).
  int max_closed_retries = 4;
  double goal_timeout_s = 180.0;   // [s] a goal not reached in this long counts as failed
  double progress_timeout_s = 60.0;// [s] a goal the robot got no nearer to (by progress_m) in this long counts as failed
  double progress_m = 0.3;         // [m] (explore_lite's progress rule: a robot held by something it cannot see)
  double decide_period_s = 1.0;    // [s] the choice of goal is looked at again this often
  double switch_gain = 0.3;        // a new frontier replaces the running goal only if this much nearer (share)
};

struct ExplorerNodeOptions
{
  std::string planner_config = "planner.yaml";   // the planner's config (its grid section); relative: beside the explorer's
  std::string name = "explorer";
  ExplorerOptions explorer;
  struct Channels
  {
    std::string rg_map = "RG_MAP";
    std::string slam_pose = "SLAM_POSE";
    std::string pose = "POSE";
    std::string gateway_hypotheses = "GATEWAY_HYPOTHESES";
    std::string global_path = "GLOBAL_PATH";
    std::string nav_goal = "NAV_GOAL";
    std::string region_name_request = "REGION_NAME_REQUEST";
    std::string status = "EXPLORER_STATUS";
  } channels;
  double persist_period_s = 2.0;   // [s] the stack and visited frontiers saved at most this often
};

// Reads config/explorer.yaml (robot radius from the robot description); throws ConfigError naming
// file and key for a missing key, a wrong type or a value out of range.
ExplorerNodeOptions load_explorer_node_options(const config::Config& cfg, const config::RobotDescription& robot);
ExplorerOptions load_explorer_options(const config::Config& cfg, const config::RobotDescription& robot);

}  // namespace rgnav::explorer
