#include "planner/planner_conversions.h"

#include <algorithm>
#include <cmath>

#include "msg/conversions.h"

namespace rgnav::planner {

NavGoal to_nav_goal(const nav_goal_t& m)
{
  NavGoal g;
  g.goal_id = m.goal_id;
  g.region_id = m.region_id;
  g.region_name = m.region_name;
  g.has_pose = m.has_pose;
  g.region_from_goal = msg::to_pose2(m.region_from_goal);
  g.position_tolerance = m.position_tolerance;
  g.heading_tolerance = m.heading_tolerance;
  g.beyond_known = m.beyond_known;
  return g;
}

nav_goal_t to_msg(const NavGoal& goal, int64_t utime)
{
  nav_goal_t m;
  m.utime = utime;
  m.goal_id = goal.goal_id;
  m.region_id = goal.region_id;
  m.region_name = goal.region_name;
  m.has_pose = goal.has_pose;
  m.region_from_goal = msg::to_msg(goal.region_from_goal);
  m.position_tolerance = goal.position_tolerance;
  m.heading_tolerance = goal.heading_tolerance;
  m.beyond_known = goal.beyond_known;
  m.cancel = false;
  return m;
}

RobotPose to_robot_pose(const region_pose_t& m)
{
  RobotPose p;
  p.utime = m.utime;
  p.region_id = m.region_id;
  p.region_from_base = msg::to_pose2(m.region_from_base);
  p.odom_from_base = msg::to_pose2(m.odom_from_base);
  return p;
}

bool cannot_pass(const ca_status_t& m)
{
  return m.mode == ca_status_t::MODE_REACTIVE || m.mode == ca_status_t::MODE_BLOCKED;
}

int8_t to_msg_status(GoalStatus s)
{
  switch (s) {
    case GoalStatus::kActive: return global_path_t::STATUS_OK;
    case GoalStatus::kReached: return global_path_t::STATUS_GOAL_REACHED;
    case GoalStatus::kCancelled: return global_path_t::STATUS_CANCELLED;
    case GoalStatus::kNoPath:
    case GoalStatus::kNone: break;
  }
  return global_path_t::STATUS_NO_PATH;
}

namespace {

region_waypoint_t waypoint(int64_t region, int64_t gateway, const Eigen::Vector2d& p, double heading)
{
  region_waypoint_t w;
  w.region_id = region;
  w.gateway_id = gateway;
  w.pose.x = p.x();
  w.pose.y = p.y();
  w.pose.theta = geometry::normalize_angle(heading);
  return w;
}

double heading_between(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double otherwise)
{
  const Eigen::Vector2d d = b - a;
  return d.squaredNorm() > 1e-12 ? std::atan2(d.y(), d.x()) : otherwise;
}

}  // namespace

global_path_t to_msg(const PathReport& report, int64_t map_version)
{
  global_path_t m;
  m.utime = report.utime;
  m.goal_id = report.goal_id;
  m.map_version = map_version;
  m.cost = std::max(0.0, report.remaining_s);
  m.status = to_msg_status(report.status);
  // The message's limit (semantic_checks.cpp); a planner's reason is a sentence.
  m.reason = report.reason.substr(0, 1000);
  const Route& route = report.route;
  for (size_t k = 0; k < route.legs.size(); ++k) {
    const RouteLeg& leg = route.legs[k];
    const auto& pts = leg.points;
    double heading = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      const bool last = i + 1 == pts.size();
      // Heading along the path; the end of the route takes the goal's heading when it has one.
      if (!last) heading = heading_between(pts[i], pts[i + 1], heading);
      else if (k + 1 == route.legs.size() && route.has_goal_heading) heading = route.goal_heading;
      int64_t gateway = 0;
      if (i == 0) gateway = leg.entry_gateway;
      if (last && leg.exit_gateway) gateway = leg.exit_gateway;
      m.waypoints.push_back(waypoint(leg.region_id, gateway, pts[i], heading));
    }
  }
  m.nwaypoints = static_cast<int32_t>(m.waypoints.size());
  return m;
}

target_list_t to_msg(const TargetList& targets)
{
  target_list_t m;
  m.utime = targets.utime;
  m.goal_id = targets.goal_id;
  for (const auto& t : targets.odom_from_target) m.odom_from_target.push_back(msg::to_msg(t));
  m.ntargets = static_cast<int32_t>(m.odom_from_target.size());
  m.max_speed = static_cast<float>(targets.max_speed);
  m.final_is_goal = targets.final_is_goal;
  return m;
}

}  // namespace rgnav::planner
