// Parameters of the planner (diss. 5.4), as config/planner.yaml names them. Defaults are the
// values documented there.
#pragma once

#include <string>

namespace rgnav::config { class Config; struct RobotDescription; }

namespace rgnav::planner {

// The region's line map and freespace rendered into a grid (region_grid.h) and the cost of
// driving near walls: a cell closer to the nearest wall or unknown cell than robot_radius is
// blocked; within clearance_margin beyond it the cost per metre rises toward the wall up to
// 1 + wall_cost; in the comfort band beyond that it is 1 + comfort_cost; then 1.
struct GridOptions
{
  double resolution = 0.1;         // [m] cell edge (a fifth of the robot's width; 0.05 m costs four times the search)
  double robot_radius = 0.26;      // [m] from the robot description
  double clearance_margin = 0.15;  // [m] wanted beyond the radius wherever the passage allows
  double comfort_width = 0.25;     // [m] the cost keeps falling this far beyond radius + margin
  double wall_cost = 3.0;          // extra cost per metre at the blocked limit
  double comfort_cost = 0.1;       // extra cost per metre in the comfort band
  int cost_levels = 4;             // open, comfort, and cost_levels - 2 levels inside the margin (quantised so
                                   // that open space forms large quads)
  double adapt_distance = 0.6;     // [m] a start or goal on a blocked cell moves to the nearest free one this near
  double neighbour_margin = 1.0;   // [m] the grid reaches this far beyond the region, into its neighbours' freespace
  double passage_depth = 0.5;      // [m] a door's opening is free this far each side of its line
  double beyond_known_reach = 1.5; // [m] a goal sent beyond_known may lie this far from the region's free cells
  double unknown_overlap = 0.15;   // [m] the robot's body may reach this far into space the region has not seen (never
                                   // into a wall): freshly mapped space is ragged at its edges (0: unknown is a wall)
  double robot_step = 1.2;         // [m] a robot cut off from its goal's free space goes straight to a goal this near
                                   // when no line of the map is in the way (a step back to where its body just was)
  double blocked_radius = 0.0;     // [m] a place where collision avoidance could not pass counts as an obstacle this wide
                                   // (radius) for a while, so that routes go round it (GlobalPlanner::block_place); 0: off
};

// Global planning over the RG graph (diss. 5.4): edge costs are times [s]; a region edge starts
// at its straight length over nominal_speed and is replaced by the region path's length once it
// is planned, and by the measured time once driven; a gateway edge is crossing_time plus, for
// doors, a learned extra that grows when a door could not be passed and shrinks when it could.
struct GlobalOptions
{
  double nominal_speed = 0.5;          // [m/s] length -> time before anything was measured
  double crossing_time = 2.0;          // [s] a gateway's crossing before it was timed
  double door_extra_time = 4.0;        // [s] added to every door: hallway gateways are preferred
  double door_failed_time = 30.0;      // [s] added to a door's cost each time it could not be passed
  double door_passed_time = -10.0;     // [s] added each time it could (never below door_extra_time)
  double closed_retry_s = 30.0;        // [s] a gateway found closed is not planned through for this long (doubled
                                       // with every further failure in a row, up to 32 times, while another way is left)
  double learning_rate = 0.3;          // weight of a new measured time in a region or gateway edge
  double crossing_reach = 2.0;         // [m] a crossing point outside a region's free cells joins the nearest one
                                       // this near (the middle of a crossing's square, seen from the region beside it)
};

// Following a route: when to replan and how the targets for collision avoidance are cut.
struct ExecutionOptions
{
  double target_spacing_min = 0.5;     // [m] targets for collision avoidance ...
  double target_spacing_max = 1.5;     // [m] ... this far apart at most (diss. 5.5.3: 0.5 - 2 m)
  double targets_ahead_m = 6.0;        // [m] targets sent reach this far ahead along the route
  double resend_period_s = 0.5;        // [s] targets re-sent (in the odometry frame of the newest pose)
  double max_speed = 0.6;              // [m/s] sent with the targets
  double max_accel = 0.4;              // [m/s^2] the drive's, for the route's predicted time
  double max_omega = 1.0;              // [rad/s] the drive's, for the route's predicted time
  double min_replan_period_s = 1.0;    // [s] at most one replan per this long
  double blocked_after_s = 6.0;        // [s] collision avoidance cannot pass this long: the passage is blocked
  double gateway_reach_m = 2.0;        // [m] blocked this near the next gateway of the route: that gateway is closed
  double closed_after_s = 30.0;        // [s] ... and with no way round, blocked this long before it counts as closed
  double switch_gain = 0.15;           // a new route replaces the running one only if this much cheaper (share)
  double off_route_m = 1.5;            // [m] farther than this from the route: replan from where the robot is
  double track_back_m = 8.0;           // [m] the robot's own track kept this long: a start cut off from the map's free
                                       // space goes back along it (GlobalPlanner::back_along_track); 0: off
  double pose_timeout_s = 2.0;         // [s] no pose this long: targets are no longer sent
};

struct PlannerOptions
{
  GridOptions grid;
  GlobalOptions global;
  ExecutionOptions execution;
};

struct PlannerNodeOptions
{
  std::string name = "planner";
  PlannerOptions planner;
  struct Channels
  {
    std::string rg_map = "RG_MAP";
    std::string pose = "POSE";
    std::string slam_pose = "SLAM_POSE";
    std::string nav_goal = "NAV_GOAL";
    std::string region_name = "REGION_NAME";
    std::string ca_status = "CA_STATUS";
    std::string global_path = "GLOBAL_PATH";
    std::string targets = "TARGETS";
  } channels;
  double persist_period_s = 5.0;       // [s] learned costs and the running goal saved at most this often
};

// Reads config/planner.yaml (robot geometry from the robot description); throws ConfigError
// naming file and key for a missing key, a wrong type or a value out of range.
PlannerNodeOptions load_planner_node_options(const config::Config& cfg, const config::RobotDescription& robot);
PlannerOptions load_planner_options(const config::Config& cfg, const config::RobotDescription& robot);

}  // namespace rgnav::planner
