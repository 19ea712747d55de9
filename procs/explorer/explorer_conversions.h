// The explorer's message seam: poses, the gateway detector's hypotheses and the planner's goal
// status in; NAV_GOAL, REGION_NAME_REQUEST and EXPLORER_STATUS out, as free functions between
// the lcmtypes and the explorer's plain types (explorer.h). Only the node adapter uses these;
// explorer_node_test round-trips them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "explorer/explorer.h"
#include "rgmap/rg_map.h"
#include "rgnav/explorer_status_t.hpp"
#include "rgnav/gateway_hypotheses_t.hpp"
#include "rgnav/global_path_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "rgnav/region_name_request_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "rgnav/slam_pose_t.hpp"

namespace rgnav::explorer {

RobotPose to_robot_pose(const slam_pose_t& m);
// The localizer's pose in the map frame (its map_from_base).
RobotPose to_robot_pose(const region_pose_t& m);

// The hypotheses of one scan, their crossing points and exit headings taken from the scan's
// base frame to the map frame with m.map_from_base. A hypothesis without a crossing point, or
// of a class that is no gateway (hallway, dead end), gives no sighting.
std::vector<GatewaySighting> to_sightings(const gateway_hypotheses_t& m);

// GLOBAL_PATH's status as the explorer reads it.
GoalOutcome to_goal_outcome(int8_t global_path_status);

// NAV_GOAL for the planner: a pose in the goal's region (its heading, any heading accepted).
nav_goal_t to_msg(const ExploreGoal& goal, int64_t utime);
// NAV_GOAL cancelling goal_id.
nav_goal_t cancel_msg(int64_t goal_id, int64_t utime);

explorer_status_t to_msg(const ExplorerStatus& s, int64_t utime);
int8_t to_msg_phase(Phase p);

// REGION_NAME_REQUEST for live region `region_id` of `map`: its freespace centroid (map frame),
// area and a short description ("room 12 m^2 with 2 gateways"); nullopt for a region the map
// does not hold live.
std::optional<region_name_request_t> name_request(const rgmap::RgMap& map, int64_t region_id, int64_t utime);

}  // namespace rgnav::explorer
