#include "viewer/viewer_node.h"

#include <spdlog/spdlog.h>

#include "rgmap/rgmap_conversions.h"
#include "rgnav/nav_goal_t.hpp"
#include "time/message_time.h"
#include "viewer/viewer_conversions.h"

namespace rgnav::viewer {

namespace {

using Clock = std::chrono::steady_clock;
// Goals clicked faster than the loop publishes them are refused beyond this.
constexpr size_t kMaxQueuedGoals = 8;

}  // namespace

ViewerNode::ViewerNode(runtime::Node& node, ViewerOptions options, const geometry::Pose2& base_from_laser, bool serve)
    : node_(node), options_(std::move(options)), base_from_laser_(base_from_laser), scene_(options_.scene)
{
  const auto& c = options_.channels;
  if (!c.rg_map.empty()) node_.subscribe<rg_map_t>(c.rg_map, [this](const rg_map_t& m) { on_rg_map(m); });
  if (!c.rg_region.empty()) node_.subscribe<region_t>(c.rg_region, [this](const region_t& m) { on_region(m); });
  if (!c.rg_graph.empty()) {
    node_.subscribe<rg_graph_t>(c.rg_graph, [this](const rg_graph_t& m) {
      note(options_.channels.rg_graph, m.utime);
      scene_.set_graph(to_graph(m));
    });
  }
  if (!c.pose.empty()) node_.subscribe<region_pose_t>(c.pose, [this](const region_pose_t& m) { on_pose(m); });
  if (!c.slam_pose.empty()) node_.subscribe<slam_pose_t>(c.slam_pose, [this](const slam_pose_t& m) { on_slam_pose(m); });
  if (!c.laser.empty()) node_.subscribe<laser_scan_t>(c.laser, [this](const laser_scan_t& m) { on_scan(m); });
  if (!c.targets.empty()) {
    node_.subscribe<target_list_t>(c.targets, [this](const target_list_t& m) {
      note(options_.channels.targets, m.utime);
      scene_.set_targets(to_targets_view(m));
    });
  }
  if (!c.trajectory.empty()) {
    node_.subscribe<trajectory_t>(c.trajectory, [this](const trajectory_t& m) {
      note(options_.channels.trajectory, m.utime);
      std::string why;
      if (auto v = to_trajectory_view(m, options_.trajectory_step_m, &why)) {
        scene_.set_trajectory(std::move(*v));
      } else {
        node_.drops().drop(options_.channels.trajectory, why);
      }
    });
  }
  if (!c.global_path.empty()) {
    node_.subscribe<global_path_t>(c.global_path, [this](const global_path_t& m) {
      note(options_.channels.global_path, m.utime);
      scene_.set_path(to_path_view(m));
    });
  }
  if (!c.objects3d.empty()) {
    node_.subscribe<objects3d_t>(c.objects3d, [this](const objects3d_t& m) {
      note(options_.channels.objects3d, m.utime);
      scene_.set_obstacles(to_obstacles_view(m));
    });
  }
  if (!c.supervisor_status.empty()) {
    node_.subscribe<supervisor_status_t>(c.supervisor_status, [this](const supervisor_status_t& m) {
      note(options_.channels.supervisor_status, m.utime);
      scene_.set_supervisor(to_supervisor_view(m));
    });
  }
  if (!c.heartbeat.empty()) {
    node_.subscribe<heartbeat_t>(c.heartbeat, [this](const heartbeat_t& m) {
      note(options_.channels.heartbeat, m.utime);
      scene_.add_heartbeat(to_heartbeat_view(m));
    });
  }

  if (serve) {
    server_ = std::make_unique<WebServer>(options_.server, [this](const ClientGoal& g) { return queue_goal(g); });
    server_->start();
    spdlog::info("viewer: http://{}:{}/", options_.server.address, server_->port());
  }
  node_.every(std::chrono::microseconds(static_cast<int64_t>(1e6 / options_.frame_hz)), [this] { flush(); });
}

ViewerNode::~ViewerNode()
{
  if (server_) server_->stop();
}

uint16_t ViewerNode::port() const { return server_ ? server_->port() : 0; }

ServerStats ViewerNode::server_stats() const { return server_ ? server_->stats() : ServerStats{}; }

void ViewerNode::note(const std::string& channel, int64_t utime) { scene_.note_message(channel, utime, Clock::now()); }

void ViewerNode::on_rg_map(const rg_map_t& m)
{
  note(options_.channels.rg_map, m.utime);
  try {
    scene_.set_map(rgmap::from_msg(m));
  } catch (const std::exception& e) {
    // Duplicate ids and the like: the bus checks cannot see them, the map model refuses them.
    node_.drops().drop(options_.channels.rg_map, e.what());
  }
}

void ViewerNode::on_region(const region_t& m)
{
  note(options_.channels.rg_region, m.utime);
  try {
    scene_.update_region(rgmap::from_msg(m));
  } catch (const std::exception& e) {
    node_.drops().drop(options_.channels.rg_region, e.what());
  }
}

void ViewerNode::on_pose(const region_pose_t& m)
{
  note(options_.channels.pose, m.utime);
  last_pose_ = Clock::now();
  has_pose_ = true;
  scene_.set_pose(to_pose_view(m, options_.channels.pose));
}

void ViewerNode::on_slam_pose(const slam_pose_t& m)
{
  note(options_.channels.slam_pose, m.utime);
  const bool pose_fresh = has_pose_ && Clock::now() - last_pose_ < std::chrono::duration<double>(options_.pose_fresh_s);
  if (!pose_fresh) scene_.set_pose(to_pose_view(m, options_.channels.slam_pose));
}

void ViewerNode::on_scan(const laser_scan_t& m)
{
  note(options_.channels.laser, m.utime);
  // Decimated in time as in space: the page needs a few scans a second, not the laser's 75.
  const auto now = Clock::now();
  if (has_scan_ && now - last_scan_ < std::chrono::duration<double>(1.0 / options_.scan_hz)) return;
  last_scan_ = now;
  has_scan_ = true;
  scene_.set_scan(to_scan_view(m, base_from_laser_, options_.scan_max_points));
}

std::string ViewerNode::queue_goal(const ClientGoal& g)
{
  if (options_.channels.nav_goal.empty()) return "this viewer sends no goals (channels.nav_goal is \"\")";
  std::lock_guard<std::mutex> lock(goals_mutex_);
  if (goals_.size() >= kMaxQueuedGoals) return "too many goals at once";
  goals_.push_back(g.request);
  return "";
}

void ViewerNode::flush()
{
  std::vector<GoalRequest> goals;
  {
    std::lock_guard<std::mutex> lock(goals_mutex_);
    goals.swap(goals_);
  }
  for (const auto& g : goals) {
    const nav_goal_t msg = to_nav_goal(g, time::wall_utime(), options_.goal_position_tolerance);
    if (node_.publish(options_.channels.nav_goal, msg)) {
      ++goals_sent_;
      spdlog::info("viewer: {} sent on {}", g.cancel ? std::string("cancel") : "goal " + std::to_string(msg.goal_id) + " to region " + std::to_string(g.region_id),
                   options_.channels.nav_goal);
    } else {
      spdlog::warn("viewer: goal to region {} refused by the bus checks", g.region_id);
    }
  }
  const auto frames = scene_.take_changed(Clock::now(), time::wall_utime());
  if (!server_) return;
  for (const auto& f : frames) server_->publish(f.topic, f.text);
}

}  // namespace rgnav::viewer
