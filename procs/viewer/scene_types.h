// What the viewer shows, as plain C++ values (no LCM): the node converts each message into one
// of these (viewer_conversions.h) and hands it to the Scene. Frames are named as in
// geometry/pose2.h; "map" is the RG map's global frame, which is also the scan mapper's
// SLAM map frame.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::viewer {

// The robot's pose from the localizer (POSE) or the scan mapper (SLAM_POSE).
struct RobotPoseView
{
  int64_t utime = 0;
  std::string source;                 // channel it came from
  geometry::Pose2 map_from_base;
  geometry::Pose2 map_from_odom;      // odometry frame in the map: places targets and trajectories
  int64_t region_id = 0;              // 0 when the source does not say
};

// One laser scan's end points in the robot's base frame (already decimated by the node's
// conversion: hits only).
struct ScanView
{
  int64_t utime = 0;
  std::vector<Eigen::Vector2d> base_points;
};

struct TargetsView
{
  int64_t utime = 0;
  int64_t goal_id = 0;
  std::vector<geometry::Pose2> odom_targets;
};

// A trajectory sampled along its chain, odometry frame.
struct TrajectoryView
{
  int64_t utime = 0;
  std::vector<Eigen::Vector2d> odom_points;
};

struct PathWaypoint
{
  int64_t region_id = 0;
  int64_t gateway_id = 0;
  geometry::Pose2 region_pose;
};

struct PathView
{
  int64_t utime = 0;
  int64_t goal_id = 0;
  int status = 0;                     // global_path_t::STATUS_*
  double cost_s = 0;
  std::string reason;
  std::vector<PathWaypoint> waypoints;
};

// Vertical rectangles seen by stereo: their footprint (the bottom edge) in the base frame at
// capture, with the odometry pose of that moment.
struct ObstaclesView
{
  int64_t utime = 0;
  geometry::Pose2 odom_from_base;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> base_edges;
};

struct ProcessRow
{
  std::string name, group;
  int state = 0;                      // process_status_t::STATE_*
  int pid = 0;
  int restarts = 0;
  std::string last_exit;
  int64_t heartbeat_age_us = -1;
  double cpu_percent = 0;
  int64_t rss_kb = 0;
};

struct SupervisorView
{
  int64_t utime = 0;
  std::string host;
  std::vector<ProcessRow> processes;
  bool robot_held = false;
  std::string alert;
};

struct HeartbeatView
{
  int64_t utime = 0;                  // [us] wall time of sending
  std::string name, host;
  int state = 0;                      // heartbeat_t::STATE_*
  double cpu_percent = 0;
  int64_t rss_kb = 0;
  int64_t messages_in = 0, messages_dropped = 0;
  std::string status;
};

}  // namespace rgnav::viewer
