#include "procs/rg_kernel/rg_kernel_options.h"

#include <cmath>

namespace rgnav::rg_kernel {

ObjectOptions load_object_options(const config::Config& s)
{
  ObjectOptions o;
  constexpr double kDeg = M_PI / 180.0;
  o.enabled = s.boolean("enabled", o.enabled);
  o.alpha_min = s.number("alpha_min_deg", o.alpha_min / kDeg, 45.0, 90.0) * kDeg;
  o.alpha_max = s.number("alpha_max_deg", o.alpha_max / kDeg, 90.0, 135.0) * kDeg;
  o.dn_max = s.number("dn_max_m", o.dn_max, 0.0, 2.0);
  o.do_min = s.number("do_min_m", o.do_min, 0.01, 5.0);
  o.max_side = s.number("max_side_m", o.max_side, o.do_min, 50.0);
  o.max_side_from_two = s.number("max_side_from_two_sides_m", o.max_side_from_two, o.do_min, 50.0);
  o.complete_three_sides = s.boolean("complete_three_sides", o.complete_three_sides);
  o.complete_two_sides = s.boolean("complete_two_sides", o.complete_two_sides);
  o.max_hypotheses = s.integer("max_hypotheses", o.max_hypotheses, 1, 100000000);
  o.outside_offset = s.number("outside_offset_m", o.outside_offset, 0.01, 2.0);
  o.min_outside_free = s.number("min_outside_free", o.min_outside_free, 0.0, 1.0);
  o.max_inside_free = s.number("max_inside_free", o.max_inside_free, 0.0, 1.0);
  o.circles = s.boolean("circles", o.circles);
  o.arc_point_gap = s.number("arc_point_gap_m", o.arc_point_gap, 0.005, 1.0);
  o.arc_min_points = static_cast<int>(s.integer("arc_min_points", o.arc_min_points, 3, 1000));
  o.circle_min_radius = s.number("circle_min_radius_m", o.circle_min_radius, 0.005, 5.0);
  o.circle_max_radius = s.number("circle_max_radius_m", o.circle_max_radius, o.circle_min_radius, 5.0);
  o.circle_max_rms = s.number("circle_max_rms_m", o.circle_max_rms, 0.0001, 0.5);
  o.arc_depth_jump = s.number("arc_depth_jump_m", o.arc_depth_jump, 0.0, 5.0);
  o.circle_min_scans = static_cast<int>(s.integer("circle_min_scans", o.circle_min_scans, 1, 100000));
  return o;
}

KernelOptions load_kernel_options(const config::Config& cfg, const config::RobotDescription& robot)
{
  KernelOptions c;
  c.build.robot_radius = robot.radius;
  const auto k = cfg.section("kernel");
  c.gateway_match_distance = k.number("gateway_match_distance_m", c.gateway_match_distance, 0.1, 5.0);
  c.merge_min_scans = static_cast<int>(k.integer("merge_min_scans", c.merge_min_scans, 1, 1000));
  c.merge_inside_ratio = k.number("merge_inside_ratio", c.merge_inside_ratio, 0.1, 1.0);
  c.merge_recent_scans =
      static_cast<int>(k.integer("merge_recent_scans", c.merge_recent_scans, c.merge_min_scans, 100000));
  c.merge_recent_ratio = k.number("merge_recent_ratio", c.merge_recent_ratio, 0.1, 1.0);
  c.entry_min_scans = static_cast<int>(k.integer("entry_min_scans", c.entry_min_scans, 0, 100000));
  c.entry_min_depth = k.number("entry_min_depth_m", c.entry_min_depth, 0.0, 100.0);
  c.entry_max_half_width = k.number("entry_max_half_width_m", c.entry_max_half_width, 0.1, 10.0);
  c.known_place.max_origin_distance =
      k.number("merge_max_origin_distance_m", c.known_place.max_origin_distance, 0.1, 20.0);
  c.late_scan_reach = k.number("late_scan_reach_m", c.late_scan_reach, 0.0, 10.0);
  c.junction_side_reach = k.number("junction_side_reach_m", c.junction_side_reach, 0.1, 10.0);
  c.junction_side_min_depth =
      k.number("junction_side_min_depth_m", c.junction_side_min_depth, 0.0, c.junction_side_reach);
  c.min_branch_width = k.number("min_branch_width_m", c.min_branch_width, 0.0, 10.0);
  c.branch_wall_tolerance = k.number("branch_wall_tolerance_m", c.branch_wall_tolerance, 0.01, 1.0);
  c.stem_ends_branch = k.boolean("stem_ends_branch", c.stem_ends_branch);
  c.gateway_line_extension = k.number("gateway_line_extension_m", c.gateway_line_extension, 0.0, 1.0);
  c.doorway_gateways = k.boolean("doorway_gateways", c.doorway_gateways);
  c.door_exits = k.boolean("door_exits", c.door_exits);
  c.stem_exits = k.boolean("stem_exits", c.stem_exits);
  c.x_branches_end = k.boolean("x_branches_end", c.x_branches_end);
  c.narrowing.max_width_ratio = k.number("gateway_narrowing_ratio", c.narrowing.max_width_ratio, 0.0, 1.0);
  c.narrowing.probe_depth = k.number("gateway_narrowing_probe_m", c.narrowing.probe_depth, 0.4, 5.0);
  const auto lines = cfg.section("line_map");
  c.build.merge.alpha_max = lines.number("merge_alpha_max_deg", 3.0, 0.1, 45.0) * M_PI / 180.0;
  c.build.merge.dl_max = lines.number("merge_dl_max_m", 0.020, 0.001, 1.0);
  c.build.merge.gap_max = lines.number("merge_gap_max_m", 0.150, 0.0, 5.0);
  c.build.merge.noise_dl_factor = lines.number("merge_noise_dl_factor", c.build.merge.noise_dl_factor, 0.0, 20.0);
  auto& al = c.build.align;
  al.enabled = lines.boolean("align_scans", al.enabled);
  al.max_distance = lines.number("align_max_distance_m", al.max_distance, 0.01, 1.0);
  al.max_translation = lines.number("align_max_correction_m", al.max_translation, 0.0, 1.0);
  al.max_rotation = lines.number("align_max_correction_deg", al.max_rotation * 180.0 / M_PI, 0.0, 10.0) * M_PI / 180.0;
  al.min_matches = static_cast<int>(lines.integer("align_min_matches", al.min_matches, 3, 100000));
  c.build.extract.noise_split_factor =
      lines.number("split_noise_factor", c.build.extract.noise_split_factor, 0.0, 20.0);
  c.build.extract.split_distance = lines.number("split_distance_m", c.build.extract.split_distance, 0.001, 1.0);
  c.build.extract.max_point_gap = lines.number("max_point_gap_m", c.build.extract.max_point_gap, 0.01, 5.0);
  c.build.extract.min_points = static_cast<int>(lines.integer("min_points", c.build.extract.min_points, 2, 1000));
  c.build.extract.min_length = lines.number("min_length_m", c.build.extract.min_length, 0.0, 10.0);
  c.build.drop_points_in_free_space = lines.boolean("drop_points_in_free_space", c.build.drop_points_in_free_space);
  c.build.seen_through_margin = lines.number("seen_through_margin_m", c.build.seen_through_margin, 0.0, 2.0);
  const auto fs = cfg.section("freespace");
  c.build.freespace_resolution = fs.number("resolution_m", c.build.freespace_resolution, 0.02, 1.0);
  c.build.freespace_max_range = fs.number("max_range_m", c.build.freespace_max_range, 1.0, 80.0);
  c.build.freespace_min_passage = fs.number("min_passage_m", c.build.freespace_min_passage, 0.0, 5.0);
  c.build.objects = load_object_options(cfg.section("objects"));
  const auto o3 = cfg.section("objects3d");
  auto& v = c.objects3d;
  v.enabled = o3.boolean("enabled", v.enabled);
  v.match_distance = o3.number("match_distance_m", v.match_distance, 0.01, 5.0);
  v.match_angle_deg = o3.number("match_angle_deg", v.match_angle_deg, 0.0, 90.0);
  v.match_size_ratio = o3.number("match_size_ratio", v.match_size_ratio, 0.0, 1.0);
  v.max_per_region = static_cast<int>(o3.integer("max_per_region", v.max_per_region, 1, 100000));
  const auto dw = cfg.section("doorways");
  auto& d = c.build.doorways;
  d.enabled = dw.boolean("enabled", d.enabled);
  d.min_width = dw.number("min_width_m", d.min_width, 0.1, 5.0);
  d.max_width = dw.number("max_width_m", d.max_width, d.min_width, 10.0);
  d.min_wall_length = dw.number("min_wall_length_m", d.min_wall_length, 0.0, 10.0);
  d.max_angle = dw.number("max_angle_deg", d.max_angle * 180.0 / M_PI, 0.0, 45.0) * M_PI / 180.0;
  d.max_offset = dw.number("max_offset_m", d.max_offset, 0.0, 1.0);
  d.wall_end_max_width = dw.number("wall_end_max_width_m", d.wall_end_max_width, 0.0, 10.0);
  d.wall_end_min_wall_length = dw.number("wall_end_min_wall_length_m", d.wall_end_min_wall_length, 0.0, 20.0);
  d.wall_end_min_angle = dw.number("wall_end_min_angle_deg", d.wall_end_min_angle * 180.0 / M_PI, 10.0, 90.0) * M_PI / 180.0;
  d.wall_end_free_radius = dw.number("wall_end_free_radius_m", d.wall_end_free_radius, 0.0, 2.0);
  d.wall_end_corner_tolerance = dw.number("wall_end_corner_tolerance_m", d.wall_end_corner_tolerance, 0.0, 2.0);
  d.wall_end_in_line_offset = dw.number("wall_end_in_line_offset_m", d.wall_end_in_line_offset, 0.0, 2.0);
  return c;
}

rgmap::GraphOptions load_graph_options(const config::Config& g)
{
  rgmap::GraphOptions c;
  c.nominal_speed = g.number("nominal_speed_mps", c.nominal_speed, 0.05, 3.0);
  c.gateway_crossing_time = g.number("gateway_crossing_time_s", c.gateway_crossing_time, 0.0, 600.0);
  return c;
}

}  // namespace rgnav::rg_kernel
