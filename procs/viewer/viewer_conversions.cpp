#include "viewer/viewer_conversions.h"

#include <algorithm>
#include <cmath>

#include "geometry/farthest_pair.h"
#include "msg/conversions.h"
#include "trajectory/trajectory_conversions.h"

namespace rgnav::viewer {

RobotPoseView to_pose_view(const region_pose_t& m, const std::string& channel)
{
  RobotPoseView v;
  v.utime = m.utime;
  v.source = channel;
  v.region_id = m.region_id;
  v.map_from_base = msg::to_pose2(m.map_from_base);
  v.map_from_odom = v.map_from_base * msg::to_pose2(m.odom_from_base).inverse();
  return v;
}

RobotPoseView to_pose_view(const slam_pose_t& m, const std::string& channel)
{
  RobotPoseView v;
  v.utime = m.utime;
  v.source = channel;
  v.map_from_base = msg::to_pose2(m.map_from_base);
  v.map_from_odom = msg::to_pose2(m.map_from_odom);
  return v;
}

ScanView to_scan_view(const laser_scan_t& m, const geometry::Pose2& base_from_laser, int max_points)
{
  ScanView v;
  v.utime = m.utime;
  const int n = static_cast<int>(m.ranges.size());
  const int stride = std::max(1, (n + max_points - 1) / std::max(1, max_points));
  for (int i = 0; i < n; i += stride) {
    const double r = m.ranges[i];
    if (!std::isfinite(r) || r <= 0 || r < m.range_min || r >= m.range_max) continue;
    const double a = m.angle_min + m.angle_increment * i;
    v.base_points.push_back(base_from_laser * Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
  }
  return v;
}

TargetsView to_targets_view(const target_list_t& m)
{
  TargetsView v;
  v.utime = m.utime;
  v.goal_id = m.goal_id;
  for (const auto& t : m.odom_from_target) v.odom_targets.push_back(msg::to_pose2(t));
  return v;
}

std::optional<TrajectoryView> to_trajectory_view(const trajectory_t& m, double step, std::string* why)
{
  const auto t = trajectory::from_msg(m, why);
  if (!t) return std::nullopt;
  TrajectoryView v;
  v.utime = m.utime;
  const auto& chain = t->chain;
  if (chain.empty()) return v;
  const double length = chain.length();
  // At most 2000 points, whatever the chain's length.
  const double ds = std::max(step, length / 2000.0);
  for (double s = 0; s < length; s += ds) v.odom_points.push_back(chain.pose_at(s).translation());
  v.odom_points.push_back(chain.end().translation());
  return v;
}

PathView to_path_view(const global_path_t& m)
{
  PathView v;
  v.utime = m.utime;
  v.goal_id = m.goal_id;
  v.status = m.status;
  v.cost_s = m.cost;
  v.reason = m.reason;
  for (const auto& w : m.waypoints) v.waypoints.push_back({w.region_id, w.gateway_id, msg::to_pose2(w.pose)});
  return v;
}

ObstaclesView to_obstacles_view(const objects3d_t& m)
{
  ObstaclesView v;
  v.utime = m.utime;
  v.odom_from_base = msg::to_pose2(m.odom_from_base);
  for (const auto& r : m.rectangles) {
    // A vertical rectangle's footprint: the two corners farthest apart seen from above.
    std::vector<Eigen::Vector2d> corners;
    for (int i = 0; i < 4; ++i) corners.emplace_back(r.corners[i][0], r.corners[i][1]);
    v.base_edges.push_back(geometry::farthest_pair(corners));
  }
  return v;
}

SupervisorView to_supervisor_view(const supervisor_status_t& m)
{
  SupervisorView v;
  v.utime = m.utime;
  v.host = m.host;
  v.robot_held = m.robot_held;
  v.alert = m.alert;
  for (const auto& p : m.processes) {
    ProcessRow r;
    r.name = p.name;
    r.group = p.group;
    r.state = p.state;
    r.pid = p.pid;
    r.restarts = p.restarts;
    r.last_exit = p.last_exit;
    r.heartbeat_age_us = p.heartbeat_age_us;
    r.cpu_percent = p.cpu_percent;
    r.rss_kb = p.rss_kb;
    v.processes.push_back(std::move(r));
  }
  return v;
}

HeartbeatView to_heartbeat_view(const heartbeat_t& m)
{
  HeartbeatView v;
  v.utime = m.utime;
  v.name = m.name;
  v.host = m.host;
  v.state = m.state;
  v.cpu_percent = m.cpu_percent;
  v.rss_kb = m.rss_kb;
  v.messages_in = m.messages_in;
  v.messages_dropped = m.messages_dropped;
  v.status = m.status;
  return v;
}

rgmap::RgGraph to_graph(const rg_graph_t& m)
{
  rgmap::RgGraph g;
  g.map_version = m.map_version;
  for (const auto& n : m.nodes) g.nodes.push_back({n.id, n.region_id, n.gateway_id, msg::to_vector(n.point)});
  for (const auto& e : m.edges) {
    rgmap::GraphEdge ge;
    ge.from = e.from_node;
    ge.to = e.to_node;
    ge.kind = e.kind == rg_graph_edge_t::KIND_GATEWAY ? rgmap::GraphEdge::Kind::kGateway : rgmap::GraphEdge::Kind::kRegion;
    ge.region_id = e.region_id;
    ge.gateway_id = e.gateway_id;
    ge.cost = e.cost;
    ge.length = e.length;
    g.edges.push_back(ge);
  }
  return g;
}

nav_goal_t to_nav_goal(const GoalRequest& r, int64_t wall_utime, double position_tolerance)
{
  nav_goal_t g{};
  g.utime = wall_utime;
  g.position_tolerance = position_tolerance;
  g.heading_tolerance = M_PI;   // any heading: a click says where, not which way
  if (r.cancel) {
    g.goal_id = 0;              // 0 cancels whatever runs
    g.cancel = true;
    return g;
  }
  g.goal_id = wall_utime / 1000;   // [ms]: unique per send from one machine, as ./rgnav goto
  g.region_id = r.region_id;
  g.has_pose = r.region_pose.has_value();
  if (r.region_pose) g.region_from_goal = msg::to_msg(*r.region_pose);
  return g;
}

}  // namespace rgnav::viewer
