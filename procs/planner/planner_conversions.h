// The planner's message seam: NAV_GOAL, POSE and CA_STATUS in, GLOBAL_PATH and TARGETS out, as
// free functions between the lcmtypes and the planner's plain types (planner.h). Only the node
// adapter uses these; planner_node_test round-trips them.
#pragma once

#include <cstdint>

#include "planner/planner.h"
#include "rgnav/ca_status_t.hpp"
#include "rgnav/global_path_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "rgnav/target_list_t.hpp"

namespace rgnav::planner {

NavGoal to_nav_goal(const nav_goal_t& m);
nav_goal_t to_msg(const NavGoal& goal, int64_t utime);

RobotPose to_robot_pose(const region_pose_t& m);

// Collision avoidance stands without a way to its targets (reactive fallbacks or blocked; not
// while it yields to a person, who passes).
bool cannot_pass(const ca_status_t& m);

// GLOBAL_PATH: every point of the route as a waypoint in its leg's region frame, headed to the
// next point (the last to the goal heading if the goal has one); the crossing point that ends a
// leg and the one that begins the next carry the gateway's id. cost is report.remaining_s.
// kNone has no message status: it goes out as STATUS_NO_PATH.
global_path_t to_msg(const PathReport& report, int64_t map_version);
int8_t to_msg_status(GoalStatus s);

target_list_t to_msg(const TargetList& targets);

}  // namespace rgnav::planner
