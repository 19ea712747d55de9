// Parameters of the viewer, as config/viewer.yaml names them. Defaults are the values
// documented there.
#pragma once

#include <chrono>
#include <string>

#include "viewer/scene.h"
#include "viewer/web_server.h"

namespace rgnav::config { class Config; struct RobotDescription; }

namespace rgnav::viewer {

// Inputs set to "" are not subscribed.
struct ViewerChannels
{
  std::string rg_map = "RG_MAP";
  std::string rg_region = "RG_REGION";
  std::string rg_graph = "RG_GRAPH";
  std::string pose = "POSE";
  std::string slam_pose = "SLAM_POSE";
  std::string laser = "LASER_FRONT";
  std::string targets = "TARGETS";
  std::string trajectory = "TRAJECTORY";
  std::string global_path = "GLOBAL_PATH";
  std::string objects3d = "OBJECTS_3D";   // the vision's 3D rectangles, drawn as their footprints
  std::string supervisor_status = "SUPERVISOR_STATUS";
  std::string heartbeat = "HEARTBEAT";
  std::string nav_goal = "NAV_GOAL";        // out: goals clicked on the page ("" = the page cannot send goals)
};

struct ViewerOptions
{
  ViewerChannels channels;
  ServerOptions server;
  SceneOptions scene;
  double frame_hz = 20.0;                   // [Hz] changed topics go to the pages this often
  double scan_hz = 5.0;                     // [Hz] laser scans taken at most this often (decimated stream)
  int scan_max_points = 180;                // points of one scan sent to the page
  double pose_fresh_s = 1.0;                // [s] POSE preferred over SLAM_POSE while no older than this
  double trajectory_step_m = 0.1;           // [m] a trajectory is drawn as points this far apart
  double goal_position_tolerance = 0.3;     // [m] goals sent from the page
};

// Reads config/viewer.yaml (all but node:); `default_web_root` is the page's folder in the
// source tree, used when http.web_root is "". Throws config::ConfigError naming file and key.
ViewerOptions load_viewer_options(const config::Config& cfg, const config::RobotDescription& robot,
                                  const std::string& default_web_root);

}  // namespace rgnav::viewer
