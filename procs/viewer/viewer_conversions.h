// The viewer's message seam: free functions from the lcmtypes it hears to the scene's plain
// types (scene_types.h), and the NAV_GOAL a click on the page becomes. Only viewer_node uses them.
#pragma once

#include <string>

#include "geometry/pose2.h"
#include "rgmap/rg_graph.h"
#include "rgnav/global_path_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "rgnav/objects3d_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "rgnav/rg_graph_t.hpp"
#include "rgnav/slam_pose_t.hpp"
#include "rgnav/supervisor_status_t.hpp"
#include "rgnav/target_list_t.hpp"
#include "rgnav/trajectory_t.hpp"
#include "viewer/client_input.h"
#include "viewer/scene_types.h"

namespace rgnav::viewer {

RobotPoseView to_pose_view(const region_pose_t& m, const std::string& channel);
RobotPoseView to_pose_view(const slam_pose_t& m, const std::string& channel);
// The scan's hits in the base frame, every k-th beam so that at most max_points remain.
ScanView to_scan_view(const laser_scan_t& m, const geometry::Pose2& base_from_laser, int max_points);
TargetsView to_targets_view(const target_list_t& m);
// The chain sampled every step metres; nullopt (with *why) when the segments do not form one.
std::optional<TrajectoryView> to_trajectory_view(const trajectory_t& m, double step, std::string* why);
PathView to_path_view(const global_path_t& m);
ObstaclesView to_obstacles_view(const objects3d_t& m);
SupervisorView to_supervisor_view(const supervisor_status_t& m);
HeartbeatView to_heartbeat_view(const heartbeat_t& m);
rgmap::RgGraph to_graph(const rg_graph_t& m);

// A goal or cancel from the page, as ./rgnav goto sends it: goal_id from the wall clock [ms],
// any heading, anywhere suitable in the region unless a pose was clicked.
nav_goal_t to_nav_goal(const GoalRequest& r, int64_t wall_utime, double position_tolerance);

}  // namespace rgnav::viewer
