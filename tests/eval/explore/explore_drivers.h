// The two ways the explorer benchmark drives the robot (explore_run.h):
//   - rgnav: the explorer (procs/explorer) and the planner (procs/planner) as their nodes feed
//     them: the RG map copied whenever its version changed, at most once per map_period_s (as
//     RG_MAP arrives); the SLAM pose to the explorer in the map frame and to the planner in the
//     map's current region (region_from_base = map_from_region^-1 * map_from_base, as the planner
//     node places SLAM_POSE); the gateway detector's hypotheses of each accepted scan through
//     GATEWAY_HYPOTHESES to the explorer's sightings; the explorer's goals through NAV_GOAL to the
//     planner; the planner's goal status back to the explorer; the explorer stepped every
//     decide period and at once when a goal ended; the planner's targets to collision avoidance.
//   - frontier: the Yamauchi baseline (frontier_explorer.h), its map-frame targets placed in the
//     odometry frame through the SLAM pose, resent every period.
#pragma once

#include <memory>

#include "explore_run.h"
#include "frontier_explorer.h"
#include "planner/planner_options.h"

namespace rgnav::explorer { struct ExplorerOptions; }

namespace rgnav::explore_eval {

std::unique_ptr<ExploreDriver> make_rg_driver(const planner::PlannerOptions& planner,
                                              const explorer::ExplorerOptions& explorer, double map_period_s);

std::unique_ptr<ExploreDriver> make_frontier_driver(const FrontierOptions& options, const geometry::Pose2& base_from_laser,
                                                    double max_speed);

}  // namespace rgnav::explore_eval
