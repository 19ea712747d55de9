// Node adapter of the viewer: the map, pose, scan, plan and status channels in (viewer_options.h
// names them), turned into the scene (scene.h) and sent to the pages by the web server on its
// own thread every 1/frame_hz; NAV_GOAL out for a goal clicked on a page. The server thread
// never touches the bus: a goal it takes is queued and published from the loop, so a client
// can neither block the LCM loop nor race it. POSE (the localizer's) is preferred while
// fresh; SLAM_POSE (the scan mapper's, while mapping) otherwise.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "rgnav/global_path_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/objects3d_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "rgnav/region_t.hpp"
#include "rgnav/rg_graph_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "rgnav/slam_pose_t.hpp"
#include "rgnav/supervisor_status_t.hpp"
#include "rgnav/target_list_t.hpp"
#include "rgnav/trajectory_t.hpp"
#include "runtime/node.h"
#include "viewer/scene.h"
#include "viewer/viewer_options.h"
#include "viewer/web_server.h"

namespace rgnav::viewer {

class ViewerNode
{
 public:
  // serve = false (--check-config): builds everything, binds nothing. Throws std::runtime_error
  // when the server cannot listen.
  ViewerNode(runtime::Node& node, ViewerOptions options, const geometry::Pose2& base_from_laser, bool serve = true);
  ~ViewerNode();
  ViewerNode(const ViewerNode&) = delete;
  ViewerNode& operator=(const ViewerNode&) = delete;

  // The port listened on (the configured one, or the one picked for port 0); 0 when not serving.
  uint16_t port() const;
  const Scene& scene() const { return scene_; }
  ServerStats server_stats() const;
  // Sends what changed and publishes queued goals (the node does this every 1/frame_hz).
  void flush();
  int64_t goals_sent() const { return goals_sent_; }

 private:
  void on_rg_map(const rg_map_t& m);
  void on_region(const region_t& m);
  void on_pose(const region_pose_t& m);
  void on_slam_pose(const slam_pose_t& m);
  void on_scan(const laser_scan_t& m);
  void note(const std::string& channel, int64_t utime);
  std::string queue_goal(const ClientGoal& g);   // server thread

  runtime::Node& node_;
  const ViewerOptions options_;
  const geometry::Pose2 base_from_laser_;
  Scene scene_;
  std::unique_ptr<WebServer> server_;
  std::chrono::steady_clock::time_point last_pose_{};   // of POSE, for preferring it
  bool has_pose_ = false;
  std::chrono::steady_clock::time_point last_scan_{};
  bool has_scan_ = false;
  std::mutex goals_mutex_;
  std::vector<GoalRequest> goals_;   // from the server thread, published by the loop
  int64_t goals_sent_ = 0;
};

}  // namespace rgnav::viewer
