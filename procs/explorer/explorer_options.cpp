#include "explorer/explorer_options.h"

#include <cmath>

#include "config/config.h"
#include "config/robot_description.h"
#include "config/string_fields.h"

namespace rgnav::explorer {

namespace {

FrontierOptions load_frontier(const config::Config& c)
{
  FrontierOptions f;
  f.wall_distance = c.number("wall_distance_m", f.wall_distance, 0.0, 2.0);
  f.min_width = c.number("min_width_m", f.min_width, 0.0, 10.0);
  f.gateway_distance = c.number("gateway_distance_m", f.gateway_distance, 0.0, 5.0);
  f.gain.range_m = c.number("gain_range_m", f.gain.range_m, 0.0, 10.0);
  f.gain.fan_rad = c.number("gain_fan_rad", f.gain.fan_rad, 0.0, M_PI);
  f.gain.step_m = c.number("gain_step_m", f.gain.step_m, 0.01, 1.0);
  f.gain.min_m2 = c.number("min_gain_m2", f.gain.min_m2, 0.0, 100.0);
  f.gain.left_min_m2 = c.number("left_region_min_gain_m2", f.gain.left_min_m2, 0.0, 100.0);
  return f;
}

StackOptions load_stack(const config::Config& c)
{
  StackOptions s;
  s.min_observations = static_cast<int>(c.integer("min_observations", s.min_observations, 1, 1000));
  s.merge_distance = c.number("merge_distance_m", s.merge_distance, 0.05, 10.0);
  s.merge_angle = c.number("merge_angle_rad", s.merge_angle, 0.0, M_PI);
  s.beyond_m = c.number("beyond_m", s.beyond_m, 0.1, 10.0);
  // Past the crossing point by less than the goal lies beyond it: reaching the goal passes it.
  s.passed_m = c.number("passed_m", s.passed_m, 0.0, s.beyond_m);
  s.breadth_first = c.boolean("breadth_first", s.breadth_first);
  s.after_regions = c.boolean("after_regions", s.after_regions);
  s.aim_search_m = c.number("aim_search_m", s.aim_search_m, 0.0, 3.0);
  return s;
}

RecoveryOptions load_recovery(const config::Config& c)
{
  RecoveryOptions r;
  r.look_at_start = c.boolean("look_at_start", r.look_at_start);
  r.heading_tolerance = c.number("heading_tolerance_rad", r.heading_tolerance, 0.05, 1.5);
  r.step_m = c.number("step_m", r.step_m, 0.1, 5.0);
  r.timeout_s = c.number("timeout_s", r.timeout_s, 1.0, 600.0);
  return r;
}

ViewOptions load_view(const config::Config& c)
{
  ViewOptions v;
  v.range_m = c.number("range_m", v.range_m, 0.1, 8.0);
  v.clearance_weight = c.number("clearance_weight", v.clearance_weight, 0.0, 100.0);
  v.heading_tolerance = c.number("heading_tolerance_rad", v.heading_tolerance, 0.05, M_PI);
  return v;
}

PlaceViewOptions load_changed(const config::Config& c)
{
  PlaceViewOptions p;
  p.radius_m = c.number("radius_m", p.radius_m, 0.2, 20.0);
  p.sample_m = c.number("sample_m", p.sample_m, 0.01, p.radius_m);
  p.changed_area_m2 = c.number("area_m2", p.changed_area_m2, 0.0, 100.0);
  p.changed_wall_m = c.number("wall_m", p.changed_wall_m, 0.0, 100.0);
  return p;
}

}  // namespace

ExplorerOptions load_explorer_options(const config::Config& cfg, const config::RobotDescription& robot)
{
  ExplorerOptions o;
  // The robot is a circle: the robot description's, not a copy here.
  o.robot_radius = robot.radius;
  o.grid.robot_radius = robot.radius;
  o.frontier = load_frontier(cfg.section("frontier"));
  o.stack = load_stack(cfg.section("stack"));
  o.recovery = load_recovery(cfg.section("recovery"));
  o.view = load_view(cfg.section("view"));
  o.changed = load_changed(cfg.section("map_changed_near"));
  const auto g = cfg.section("goals");
  o.goal_tolerance = g.number("tolerance_m", o.goal_tolerance, 0.05, 5.0);
  o.gateway_goal_tolerance = g.number("gateway_tolerance_m", o.gateway_goal_tolerance, 0.05, 5.0);
  o.visited_radius = g.number("visited_radius_m", o.visited_radius, 0.0, 20.0);
  o.retry_after_s = g.number("retry_after_s", o.retry_after_s, 0.0, 86400.0);
  o.max_attempts = static_cast<int>(g.integer("max_attempts", o.max_attempts, 1, 100));
  o.max_closed_retries = static_cast<int>(g.integer("max_closed_retries", o.max_closed_retries, 1, 100));
  o.goal_timeout_s = g.number("timeout_s", o.goal_timeout_s, 1.0, 86400.0);
  o.progress_timeout_s = g.number("progress_timeout_s", o.progress_timeout_s, 1.0, 86400.0);
  o.progress_m = g.number("progress_m", o.progress_m, 0.0, 10.0);
  o.decide_period_s = g.number("decide_period_s", o.decide_period_s, 0.05, 60.0);
  o.switch_gain = g.number("switch_gain", o.switch_gain, 0.0, 1.0);
  return o;
}

ExplorerNodeOptions load_explorer_node_options(const config::Config& cfg, const config::RobotDescription& robot)
{
  ExplorerNodeOptions o;
  o.name = cfg.section("node").string("name", o.name);
  o.explorer = load_explorer_options(cfg, robot);
  o.planner_config = cfg.section("view").string("planner_config", "planner.yaml");
  if (o.planner_config.empty()) cfg.section("view").fail("planner_config", "must name the planner's config (its grid)");
  const auto ch = cfg.section("channels");
  auto& c = o.channels;
  config::read_strings(ch, {{"rg_map", &c.rg_map},
                            {"slam_pose", &c.slam_pose},
                            {"pose", &c.pose},
                            {"gateway_hypotheses", &c.gateway_hypotheses},
                            {"global_path", &c.global_path},
                            {"nav_goal", &c.nav_goal},
                            {"region_name_request", &c.region_name_request},
                            {"status", &c.status}});
  // An input may be "" (not subscribed: no localizer, no gateway detector); the map, the
  // planner's answers and what the explorer publishes must have a channel.
  if (c.rg_map.empty()) ch.fail("rg_map", "must name a channel (the explorer explores the RG map)");
  if (c.global_path.empty()) ch.fail("global_path", "must name a channel (the planner's answers to its goals)");
  if (c.nav_goal.empty()) ch.fail("nav_goal", "must name a channel (the explorer's goals go there)");
  if (c.region_name_request.empty()) ch.fail("region_name_request", "must name a channel");
  if (c.status.empty()) ch.fail("status", "must name a channel");
  if (c.pose.empty() && c.slam_pose.empty())
    ch.fail("pose", "pose and slam_pose cannot both be \"\" (the explorer needs the robot's pose)");
  o.persist_period_s = cfg.section("persist").number("period_s", o.persist_period_s, 0.1, 3600.0);
  return o;
}

}  // namespace rgnav::explorer
