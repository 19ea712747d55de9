#include "planner/planner_options.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "config/config.h"
#include "config/robot_description.h"
#include "config/string_fields.h"

namespace rgnav::planner {

namespace {

GridOptions load_grid(const config::Config& c, const config::RobotDescription& robot)
{
  GridOptions g;
  // The robot is a circle: the grid blocks every cell nearer a wall than its radius.
  g.robot_radius = robot.radius;
  g.resolution = c.number("resolution_m", g.resolution, 0.01, 0.5);
  g.clearance_margin = c.number("clearance_margin_m", g.clearance_margin, 0.0, 2.0);
  g.comfort_width = c.number("comfort_width_m", g.comfort_width, 0.0, 5.0);
  g.wall_cost = c.number("wall_cost", g.wall_cost, 0.0, 100.0);
  g.comfort_cost = c.number("comfort_cost", g.comfort_cost, 0.0, g.wall_cost);
  // Open, comfort, and at least one level inside the margin.
  g.cost_levels = static_cast<int>(c.integer("cost_levels", g.cost_levels, 3, 64));
  g.adapt_distance = c.number("adapt_distance_m", g.adapt_distance, 0.0, 5.0);
  g.neighbour_margin = c.number("neighbour_margin_m", g.neighbour_margin, 0.0, 10.0);
  g.passage_depth = c.number("passage_depth_m", g.passage_depth, 0.0, 5.0);
  g.beyond_known_reach = c.number("beyond_known_reach_m", g.beyond_known_reach, g.adapt_distance, 10.0);
  g.unknown_overlap = c.number("unknown_overlap_m", g.unknown_overlap, 0.0, g.robot_radius);
  g.blocked_radius = c.number("blocked_radius_m", g.blocked_radius, 0.0, 2.0);   // 0: no place is blocked
  g.robot_step = c.number("robot_step_m", g.robot_step, 0.0, 5.0);
  return g;
}

GlobalOptions load_global(const config::Config& c)
{
  GlobalOptions g;
  g.nominal_speed = c.number("nominal_speed_mps", g.nominal_speed, 0.05, 5.0);
  g.crossing_time = c.number("crossing_time_s", g.crossing_time, 0.0, 600.0);
  g.door_extra_time = c.number("door_extra_time_s", g.door_extra_time, 0.0, 600.0);
  g.door_failed_time = c.number("door_failed_time_s", g.door_failed_time, 0.0, 3600.0);
  g.door_passed_time = c.number("door_passed_time_s", g.door_passed_time, -3600.0, 0.0);
  g.closed_retry_s = c.number("closed_retry_s", g.closed_retry_s, 1.0, 86400.0);
  g.learning_rate = c.number("learning_rate", g.learning_rate, 0.0, 1.0);
  g.crossing_reach = c.number("crossing_reach_m", g.crossing_reach, 0.0, 20.0);
  return g;
}

ExecutionOptions load_execution(const config::Config& c, const config::RobotDescription& robot)
{
  ExecutionOptions e;
  e.target_spacing_min = c.number("target_spacing_min_m", e.target_spacing_min, 0.1, 5.0);
  e.target_spacing_max = c.number("target_spacing_max_m", e.target_spacing_max, e.target_spacing_min, 10.0);
  e.targets_ahead_m = c.number("targets_ahead_m", e.targets_ahead_m, e.target_spacing_max, 100.0);
  e.resend_period_s = c.number("resend_period_s", e.resend_period_s, 0.05, 10.0);
  e.max_speed = c.number("max_speed_mps", e.max_speed, 0.05, 5.0);
  // The planner never asks for more than the drive can do: the robot description decides, so
  // a slower robot needs no edit here.
  if (e.max_speed > robot.drive.max_v) {
    spdlog::info("{}: max_speed_mps {:.2f} capped at the robot's drive.max_v {:.2f}", c.origin(), e.max_speed,
                 robot.drive.max_v);
    e.max_speed = robot.drive.max_v;
  }
  // The route's predicted time uses the limits collision avoidance drives with, which the
  // drive itself bounds.
  e.max_accel = std::min(c.number("max_accel_mps2", e.max_accel, 0.01, 10.0), robot.drive.max_accel);
  e.max_omega = std::min(c.number("max_omega_radps", e.max_omega, 0.01, 10.0), robot.drive.max_omega);
  e.min_replan_period_s = c.number("min_replan_period_s", e.min_replan_period_s, 0.0, 600.0);
  e.blocked_after_s = c.number("blocked_after_s", e.blocked_after_s, 0.5, 600.0);
  e.gateway_reach_m = c.number("gateway_reach_m", e.gateway_reach_m, 0.0, 20.0);
  e.closed_after_s = c.number("closed_after_s", e.closed_after_s, e.blocked_after_s, 3600.0);
  e.switch_gain = c.number("switch_gain", e.switch_gain, 0.0, 1.0);
  e.off_route_m = c.number("off_route_m", e.off_route_m, 0.1, 50.0);
  e.track_back_m = c.number("track_back_m", e.track_back_m, 0.0, 100.0);
  // Targets are re-sent every resend period; a pose older than that many periods stops them.
  e.pose_timeout_s = c.number("pose_timeout_s", e.pose_timeout_s, e.resend_period_s, 60.0);
  return e;
}

}  // namespace

PlannerOptions load_planner_options(const config::Config& cfg, const config::RobotDescription& robot)
{
  PlannerOptions o;
  o.grid = load_grid(cfg.section("grid"), robot);
  o.global = load_global(cfg.section("global"));
  o.execution = load_execution(cfg.section("execution"), robot);
  return o;
}

PlannerNodeOptions load_planner_node_options(const config::Config& cfg, const config::RobotDescription& robot)
{
  PlannerNodeOptions o;
  o.name = cfg.section("node").string("name", o.name);
  o.planner = load_planner_options(cfg, robot);
  const auto ch = cfg.section("channels");
  auto& c = o.channels;
  config::read_strings(ch, {{"rg_map", &c.rg_map},
                            {"pose", &c.pose},
                            {"slam_pose", &c.slam_pose},
                            {"nav_goal", &c.nav_goal},
                            {"region_name", &c.region_name},
                            {"ca_status", &c.ca_status},
                            {"global_path", &c.global_path},
                            {"targets", &c.targets}});
  // Inputs may be "" (not subscribed: a planner on a saved map needs no RG_MAP); what it
  // publishes must go somewhere.
  if (c.global_path.empty()) ch.fail("global_path", "must name a channel");
  if (c.targets.empty()) ch.fail("targets", "must name a channel");
  if (c.nav_goal.empty()) ch.fail("nav_goal", "must name a channel (the planner's goals come from it)");
  if (c.pose.empty() && c.slam_pose.empty()) ch.fail("pose", "pose and slam_pose cannot both be \"\" (the planner needs the robot's pose)");
  o.persist_period_s = cfg.section("persist").number("period_s", o.persist_period_s, 0.1, 3600.0);
  return o;
}

}  // namespace rgnav::planner
