#include "collision_avoidance/ca_options.h"

#include <algorithm>
#include <cmath>

namespace rgnav::collision_avoidance {

CaNodeOptions load_ca_options(const config::Config& root, const config::RobotDescription& robot)
{
  CaNodeOptions o;
  const auto ch = root.section("channels");
  o.channels.targets = ch.string("targets", o.channels.targets);
  o.channels.nav_goal = ch.string("nav_goal", o.channels.nav_goal);
  o.channels.odometry = ch.string("odometry", o.channels.odometry);
  o.channels.laser = ch.string("laser", o.channels.laser);
  o.channels.obstacles = ch.string("obstacles", o.channels.obstacles);
  o.channels.lld_status = ch.string("lld_status", o.channels.lld_status);
  o.channels.trajectory = ch.string("trajectory", o.channels.trajectory);
  o.channels.status = ch.string("status", o.channels.status);

  auto& c = o.ca;
  c.planner.robot_radius = robot.radius;
  c.base_from_laser = robot.laser_front.base_from_laser;

  const auto map = root.section("local_map");
  c.map.max_scans = static_cast<int>(map.integer("max_scans", c.map.max_scans, 1, 100));
  c.map.max_age = map.number("max_age_s", c.map.max_age, 0.05, 10.0);
  c.map.max_range = map.number("max_range_m", c.map.max_range, 0.5, 80.0);
  c.map.cell = map.number("cell_m", c.map.cell, 0.02, 1.0);
  c.map.grid_occupied_min = static_cast<int>(map.integer("grid_occupied_min", c.map.grid_occupied_min, 1, 100));
  c.map.static_after = map.number("static_after_s", c.map.static_after, 0.0, 30.0);
  c.map.occupancy_gap = map.number("occupancy_gap_s", c.map.occupancy_gap, 0.01, 5.0);
  c.map.memory = map.number("memory_s", c.map.memory, 0.0, 120.0);
  c.map.memory_cell = map.number("memory_cell_m", c.map.memory_cell, 0.01, 0.5);
  c.map.clear_margin = map.number("clear_margin_m", c.map.clear_margin, 0.0, 1.0);
  c.map.view_interval = map.number("view_interval_s", c.map.view_interval, 0.01, 10.0);

  const auto ppl = root.section("people");
  auto& po = c.map.people;
  po.cluster_distance = ppl.number("cluster_distance_m", po.cluster_distance, 0.05, 2.0);
  po.min_points = static_cast<int>(ppl.integer("min_points", po.min_points, 1, 100));
  po.gate = ppl.number("gate_m", po.gate, 0.05, 5.0);
  po.history = ppl.number("history_s", po.history, 0.1, 5.0);
  po.lost_after = ppl.number("lost_after_s", po.lost_after, 0.05, 5.0);
  po.min_speed = ppl.number("min_speed_mps", po.min_speed, 0.0, 5.0);
  po.max_speed = ppl.number("max_speed_mps", po.max_speed, 0.1, 10.0);
  po.horizon = ppl.number("horizon_s", po.horizon, 0.0, 10.0);
  po.step = ppl.number("step_s", po.step, 0.05, 2.0);
  po.max_still_there = ppl.number("max_still_there", po.max_still_there, 0.0, 1.0);
  po.stopped_memory = ppl.number("stopped_memory_s", po.stopped_memory, 0.0, 600.0);
  po.stopped_min_travel = ppl.number("stopped_min_travel_m", po.stopped_min_travel, 0.0, 10.0);
  po.stopped_min_moving = ppl.number("stopped_min_moving_s", po.stopped_min_moving, 0.0, 60.0);

  const auto pl = root.section("planner");
  c.planner.safety_margin = pl.number("safety_margin_m", c.planner.safety_margin, 0.0, 1.0);
  c.planner.kappa_max = pl.number("kappa_max", c.planner.kappa_max, 0.1, 20.0);
  c.planner.check_step = pl.number("check_step_m", c.planner.check_step, 0.005, 0.5);
  c.planner.detour_offsets = pl.numbers("detour_offsets_m", c.planner.detour_offsets, 0.05, 5.0, 0, 16);
  c.planner.max_length_ratio = pl.number("max_length_ratio", c.planner.max_length_ratio, 1.0, 20.0);
  c.planner.slow_band = pl.number("slow_band_m", c.planner.slow_band, 0.0, 5.0);
  c.planner.near_length = pl.number("near_length_m", c.planner.near_length, 0.0, 5.0);
  c.planner.near_margin = pl.number("near_margin_m", c.planner.near_margin, 0.0, 2.0);
  c.planner.slow_speed = pl.number("slow_speed_mps", c.planner.slow_speed, 0.05, 2.0);
  c.planner.turn_first_angle = pl.number("turn_first_angle_rad", c.planner.turn_first_angle, 0.2, 3.2);
  c.planner.limits.v_max = pl.number("v_max_mps", c.planner.limits.v_max, 0.05, 2.0);
  c.planner.limits.a_max = pl.number("a_max_mps2", c.planner.limits.a_max, 0.05, 5.0);
  c.planner.limits.a_lat_max = pl.number("a_lat_max_mps2", c.planner.limits.a_lat_max, 0.05, 5.0);
  c.planner.limits.omega_max = pl.number("omega_max_radps", c.planner.limits.omega_max, 0.05, 5.0);
  c.planner.limits.alpha_max = pl.number("alpha_max_radps2", c.planner.limits.alpha_max, 0.05, 20.0);
  c.planner.limits.omega_jump_max = pl.number("omega_jump_max_radps", c.planner.limits.omega_jump_max, 0.0, 2.0);
  c.a_max = c.planner.limits.a_max;
  c.omega_max = c.planner.limits.omega_max;

  const auto re = root.section("reactive");
  c.reactive.dto_min = re.number("dto_min_m", c.reactive.dto_min, 0.1, 5.0);
  c.reactive.dto_max = re.number("dto_max_m", c.reactive.dto_max, 0.2, 10.0);
  if (c.reactive.dto_max <= c.reactive.dto_min) re.fail("dto_max_m", "must exceed dto_min_m");
  c.reactive.corridor_half_width = c.planner.robot_radius + c.planner.safety_margin;
  c.reactive.v_max = re.number("v_max_mps", c.reactive.v_max, 0.01, 1.0);
  c.reactive.step_length = re.number("step_length_m", c.reactive.step_length, 0.1, 3.0);
  c.reactive.max_turn = re.number("max_turn_rad", c.reactive.max_turn, 0.1, 3.2);

  const auto gp = root.section("detour");
  c.grid.cell = gp.number("cell_m", c.grid.cell, 0.02, 0.5);
  c.grid.margin = gp.number("margin_m", c.grid.margin, 0.5, 10.0);
  c.grid.max_extent = gp.number("max_extent_m", c.grid.max_extent, 2.0, 50.0);
  c.grid.comfort = gp.number("comfort_m", c.grid.comfort, 0.0, 3.0);
  c.grid.comfort_weight = gp.number("comfort_weight", c.grid.comfort_weight, 0.0, 100.0);
  c.grid.shadow_cost = gp.number("shadow_cost", c.grid.shadow_cost, 1.0, 100.0);
  c.detour_speed = gp.number("speed_mps", c.detour_speed, 0.05, 2.0);
  c.squeeze_margin = gp.number("squeeze_margin_m", c.squeeze_margin, 0.0, 1.0);
  if (c.squeeze_margin >= c.planner.safety_margin && c.squeeze_margin > 0.0)
    gp.fail("squeeze_margin_m", "must be below planner.safety_margin_m (0: off)");
  c.squeeze_speed = gp.number("squeeze_speed_mps", c.squeeze_speed, 0.05, 1.0);
  c.squeeze_people = gp.number("squeeze_people_m", c.squeeze_people, 0.0, 20.0);
  if (c.grid.margin < c.planner.robot_radius + c.planner.safety_margin + c.grid.comfort)
    gp.fail("margin_m", "must cover the clearance (robot radius + safety margin) plus comfort_m");

  const auto be = root.section("behaviour");
  c.fallback_wait = be.number("fallback_wait_s", c.fallback_wait, 0.0, 30.0);
  c.backoff_length = be.number("backoff_length_m", c.backoff_length, 0.05, 2.0);
  c.headway = be.number("headway_m", c.headway, 0.01, 5.0);
  c.yield_after = be.number("yield_after_s", c.yield_after, 0.5, 600.0);
  c.yield_reach = be.number("yield_reach_m", c.yield_reach, 0.0, 3.0);
  c.backoff_speed = be.number("backoff_speed_mps", c.backoff_speed, 0.02, 0.5);
  c.give_way.length = be.number("give_way_length_m", c.give_way.length, 0.1, 5.0);
  c.give_way.min_length = be.number("give_way_min_length_m", c.give_way.min_length, 0.05, c.give_way.length);
  c.give_way.spread = be.number("give_way_spread_rad", c.give_way.spread, 0.0, M_PI);
  c.give_way_speed = be.number("give_way_speed_mps", c.give_way_speed, 0.02, 1.0);
  c.give_way_timeout = be.number("give_way_timeout_s", c.give_way_timeout, 1.0, 600.0);
  c.retrace_own_track = be.boolean("retrace_own_track", c.retrace_own_track);
  c.own_track.max_back = be.number("retrace_max_m", c.own_track.max_back, 0.2, 10.0);
  c.own_track.max_length = std::max(c.own_track.max_length, c.own_track.max_back);
  c.own_track.tolerance = be.number("retrace_tolerance_m", c.own_track.tolerance, 0.0, 0.2);
  c.retrace_speed = be.number("retrace_speed_mps", c.retrace_speed, 0.02, 0.5);
  const auto yi = root.section("yield");
  auto& y = c.give_way.yield;
  c.yield_sideways_after = yi.number("after_s", c.yield_sideways_after, 0.0, 600.0);
  c.yield_head_on_after = yi.number("head_on_after_s", c.yield_head_on_after, 0.0, 600.0);
  c.yield_notice = yi.number("notice_m", c.yield_notice, 0.0, 20.0);
  c.yield_notice_stopped = yi.number("notice_stopped_m", c.yield_notice_stopped, 0.0, 20.0);
  y.path_half_width = yi.number("path_half_width_m", y.path_half_width, 0.1, 3.0);
  y.extra = yi.number("extra_m", y.extra, 0.0, 3.0);
  y.spot_margin = yi.number("spot_margin_m", y.spot_margin, 0.0, 2.0);
  y.way_margin = yi.number("way_margin_m", y.way_margin, 0.0, 1.0);
  y.max_travel = yi.number("max_travel_m", y.max_travel, 0.5, 30.0);
  y.person_keep = yi.number("person_keep_m", y.person_keep, 0.0, 3.0);
  y.in_path_cost = yi.number("in_path_cost", y.in_path_cost, 1.0, 100.0);
  y.downstream_cost = yi.number("downstream_cost", y.downstream_cost, 1.0, 100.0);
  y.cell = yi.number("cell_m", y.cell, 0.02, 0.5);
  y.shadow_cost = yi.number("shadow_cost", y.shadow_cost, 1.0, 100.0);
  c.yield_speed = yi.number("speed_mps", c.yield_speed, 0.02, 1.0);
  y.watch_half_width = yi.number("watch_half_width_m", y.watch_half_width, 0.1, 5.0);
  y.watch_behind = yi.number("watch_behind_m", y.watch_behind, 0.0, 20.0);
  c.pass_settle = yi.number("pass_settle_s", c.pass_settle, 0.0, 60.0);
  c.standing_go_after = yi.number("standing_go_after_s", c.standing_go_after, 0.0, 600.0);
  c.yield_wait_timeout = yi.number("wait_timeout_s", c.yield_wait_timeout, 1.0, 600.0);
  c.yield_timeout = yi.number("timeout_s", c.yield_timeout, 1.0, 3600.0);
  if (c.yield_timeout < c.yield_wait_timeout) yi.fail("timeout_s", "must be at least wait_timeout_s");

  c.reach_radius = be.number("reach_radius_m", c.reach_radius, 0.05, 2.0);
  c.goal_tolerance = be.number("goal_tolerance_m", c.goal_tolerance, 0.01, 1.0);
  c.lookahead_targets = static_cast<int>(be.integer("lookahead_targets", c.lookahead_targets, 1, 10));
  c.max_target_distance = be.number("max_target_distance_m", c.max_target_distance, 1.0, 100.0);
  c.scan_timeout = be.number("scan_timeout_s", c.scan_timeout, 0.05, 10.0);
  c.update_period = be.number("update_period_s", c.update_period, 0.0, 2.0);
  c.refresh_period = be.number("refresh_period_s", c.refresh_period, 0.05, 10.0);
  c.resend_tolerance = be.number("resend_tolerance_m", c.resend_tolerance, 0.0, 2.0);
  c.replan_cross_track = be.number("replan_cross_track_m", c.replan_cross_track, 0.02, 2.0);
  return o;
}

}  // namespace rgnav::collision_avoidance
