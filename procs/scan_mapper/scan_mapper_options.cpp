#include "scan_mapper/scan_mapper_options.h"

#include <cmath>

namespace rgnav::scan_mapper {
namespace {
constexpr double kDeg = M_PI / 180.0;

// A correlative search's options: the same keys for the registration's retries
// (registration.correlative) and the loop closure's search (loop_closure.correlative), the
// defaults each one's own.
CorrelativeOptions load_correlative(const config::Config& cor, CorrelativeOptions c)
{
  c.resolution_m = cor.number("resolution_m", c.resolution_m, 0.01, 0.5);
  c.sigma_m = cor.number("sigma_m", c.sigma_m, 0.005, 1.0);
  c.coarse_factor = static_cast<int>(cor.integer("coarse_factor", c.coarse_factor, 1, 64));
  c.max_angular_step_deg = cor.number("max_angular_step_deg", c.max_angular_step_deg, 0.05, 10.0);
  return c;
}
}  // namespace

ScanMapperOptions load_scan_mapper_options(const config::Config& c, const config::RobotDescription& robot)
{
  ScanMapperOptions o;
  const auto& mount = robot.laser_front.base_from_laser;
  o.base_from_laser = Pose2{mount.x(), mount.y(), normalize_angle(mount.theta())};
  const auto gate = c.section("gating");
  o.min_travel_m = gate.number("min_travel_m", o.min_travel_m, 0.0, 10.0);
  o.min_rotation_rad = gate.number("min_rotation_deg", o.min_rotation_rad / kDeg, 0.0, 180.0) * kDeg;
  o.max_odometry_extrapolation_us =
      static_cast<int64_t>(gate.number("max_odometry_extrapolation_s", 0.1, 0.0, 10.0) * 1e6);

  const auto pts = c.section("points");
  o.points.min_range_m = pts.number("min_range_m", o.points.min_range_m, 0.0, 10.0);
  o.points.max_range_m = pts.number("max_range_m", o.points.max_range_m, 0.5, 100.0);
  o.points.min_spacing_m = pts.number("min_spacing_m", o.points.min_spacing_m, 0.0, 1.0);
  const auto beam = pts.section("beam_normals");
  o.normals.beam_max_gap_m = beam.number("max_gap_m", o.normals.beam_max_gap_m, 0.0, 10.0);
  o.normals.beam_max_bend_rad = beam.number("max_bend_deg", o.normals.beam_max_bend_rad / kDeg, 0.0, 45.0) * kDeg;

  const auto reg = c.section("registration");
  o.local_map_scans = static_cast<int>(reg.integer("local_map_scans", o.local_map_scans, 1, 200));
  o.min_inlier_ratio = reg.number("min_inlier_ratio", o.min_inlier_ratio, 0.0, 1.0);
  o.min_accept_inlier_ratio = reg.number("min_accept_inlier_ratio", o.min_accept_inlier_ratio, 0.0, 1.0);
  o.local_window.linear_m = reg.number("retry_window_m", o.local_window.linear_m, 0.0, 5.0);
  o.local_window.angular_rad = reg.number("retry_window_deg", o.local_window.angular_rad / kDeg, 0.0, 90.0) * kDeg;
  o.max_innovation_chi2 = reg.number("max_innovation_chi2", o.max_innovation_chi2, 0.1, 1e9);
  o.turn_check_sigmas = reg.number("turn_check_sigmas", o.turn_check_sigmas, 0.0, 100.0);
  o.turn_min_inlier_gain = reg.number("turn_min_inlier_gain", o.turn_min_inlier_gain, 0.0, 1.0);
  o.turn_max_rms_ratio = reg.number("turn_max_rms_ratio", o.turn_max_rms_ratio, 0.0, 100.0);
  const auto icp = reg.section("icp");
  o.icp.max_iterations = static_cast<int>(icp.integer("max_iterations", o.icp.max_iterations, 1, 500));
  o.icp.initial_max_distance_m = icp.number("initial_max_distance_m", o.icp.initial_max_distance_m, 0.01, 5.0);
  o.icp.final_max_distance_m = icp.number("final_max_distance_m", o.icp.final_max_distance_m, 0.005, 5.0);
  o.icp.decay = icp.number("decay", o.icp.decay, 0.1, 1.0);
  o.icp.inlier_distance_m = icp.number("inlier_distance_m", o.icp.inlier_distance_m, 0.005, 5.0);
  o.icp.point_sigma_m = icp.number("point_sigma_m", o.icp.point_sigma_m, 0.001, 1.0);
  o.icp.covariance_inflation = icp.number("covariance_inflation", o.icp.covariance_inflation, 1.0, 1e4);
  o.icp.max_normal_angle_deg = icp.number("max_normal_angle_deg", o.icp.max_normal_angle_deg, 10.0, 180.0);
  o.icp.degenerate_min_points = icp.number("degenerate_min_points", o.icp.degenerate_min_points, 0.0, 1e6);
  o.icp.degenerate_variance_m2 = icp.number("degenerate_variance_m2", o.icp.degenerate_variance_m2, 1e-4, 1e4);
  if (o.icp.final_max_distance_m > o.icp.initial_max_distance_m)
    c.fail("registration.icp.final_max_distance_m", "must not exceed initial_max_distance_m");
  const auto mov = reg.section("moving_points");
  o.moving_points.margin_m = mov.number("margin_m", o.moving_points.margin_m, 0.0, 5.0);
  o.moving_points.max_incidence_deg = mov.number("max_incidence_deg", o.moving_points.max_incidence_deg, 0.0, 90.0);
  o.correlative = load_correlative(reg.section("correlative"), o.correlative);

  const auto odo = c.section("odometry_noise");
  o.odometry_noise.trans_per_m = odo.number("trans_per_m", o.odometry_noise.trans_per_m, 0.0, 10.0);
  o.odometry_noise.rot_per_rad = odo.number("rot_per_rad", o.odometry_noise.rot_per_rad, 0.0, 10.0);
  o.odometry_noise.rot_per_m = odo.number("rot_per_m", o.odometry_noise.rot_per_m, 0.0, 10.0);
  o.odometry_noise.min_trans_m = odo.number("min_trans_m", o.odometry_noise.min_trans_m, 1e-6, 10.0);
  o.odometry_noise.min_rot_rad = odo.number("min_rot_deg", o.odometry_noise.min_rot_rad / kDeg, 1e-4, 180.0) * kDeg;
  const auto adapt = odo.section("adapt");
  o.odometry_noise.adapt_window_scans =
      static_cast<int>(adapt.integer("window_scans", o.odometry_noise.adapt_window_scans, 0, 100000));
  o.odometry_noise.adapt_max_scale = adapt.number("max_scale", o.odometry_noise.adapt_max_scale, 1.0, 100.0);
  o.odometry_noise.adapt_degeneracy = adapt.boolean("degeneracy", o.odometry_noise.adapt_degeneracy);
  const auto scale = c.section("odometry_scale");
  o.odometry_scale.window_m = scale.number("window_m", o.odometry_scale.window_m, 0.0, 1e6);
  o.odometry_scale.min_step_m = scale.number("min_step_m", o.odometry_scale.min_step_m, 0.0, 10.0);
  o.odometry_scale.min_travel_m = scale.number("min_travel_m", o.odometry_scale.min_travel_m, 0.0, 1e6);
  o.odometry_scale.max_error = scale.number("max_error", o.odometry_scale.max_error, 0.0, 0.5);

  const auto lc = c.section("loop_closure");
  auto& l = o.loop;
  l.enabled = lc.boolean("enabled", l.enabled);
  l.every_n_scans = static_cast<int>(lc.integer("every_n_scans", l.every_n_scans, 1, 1000));
  l.min_node_gap = static_cast<int>(lc.integer("min_node_gap", l.min_node_gap, 1, 100000));
  l.min_path_gap_m = lc.number("min_path_gap_m", l.min_path_gap_m, 0.0, 1e4);
  l.search_radius_m = lc.number("search_radius_m", l.search_radius_m, 0.1, 100.0);
  l.submap_half_nodes = static_cast<int>(lc.integer("submap_half_nodes", l.submap_half_nodes, 0, 1000));
  l.submap_radius_m = lc.number("submap_radius_m", l.submap_radius_m, 1.0, 100.0);
  const auto drift = lc.section("drift");
  l.drift.trans_var_per_m = drift.number("trans_var_per_m", l.drift.trans_var_per_m, 0.0, 10.0);
  l.drift.rot_var_per_m = drift.number("rot_var_per_m", l.drift.rot_var_per_m, 0.0, 10.0);
  l.drift.rot_var_per_rad = drift.number("rot_var_per_rad", l.drift.rot_var_per_rad, 0.0, 10.0);
  l.gate_sigmas = lc.number("gate_sigmas", l.gate_sigmas, 0.5, 10.0);
  l.window_base_m = lc.number("window_base_m", l.window_base_m, 0.0, 20.0);
  l.window_max_m = lc.number("window_max_m", l.window_max_m, 0.0, 20.0);
  l.angular_window_base_rad = lc.number("angular_window_base_deg", l.angular_window_base_rad / kDeg, 0.0, 180.0) * kDeg;
  l.angular_window_max_rad = lc.number("angular_window_max_deg", l.angular_window_max_rad / kDeg, 0.0, 180.0) * kDeg;
  if (l.window_max_m < l.window_base_m) lc.fail("window_max_m", "must not be below window_base_m");
  if (l.angular_window_max_rad < l.angular_window_base_rad)
    lc.fail("angular_window_max_deg", "must not be below angular_window_base_deg");
  l.direct_max_sigma_m = lc.number("direct_max_sigma_m", l.direct_max_sigma_m, 0.0, 100.0);
  l.direct_max_chi2 = lc.number("direct_max_chi2", l.direct_max_chi2, 0.0, 1e6);
  l.confirm_within_nodes = static_cast<int>(lc.integer("confirm_within_nodes", l.confirm_within_nodes, 1, 100000));
  l.witness_min_travel_m = lc.number("witness_min_travel_m", l.witness_min_travel_m, 0.0, 1e4);
  l.consistency.trans_m = lc.number("consistency_m", l.consistency.trans_m, 0.001, 10.0);
  l.consistency.rot_rad = lc.number("consistency_deg", l.consistency.rot_rad / kDeg, 0.01, 90.0) * kDeg;
  l.min_score = lc.number("min_score", l.min_score, 0.0, 1.0);
  l.max_ambiguity = lc.number("max_ambiguity", l.max_ambiguity, 0.0, 1.0);
  l.ambiguity_distance_m = lc.number("ambiguity_distance_m", l.ambiguity_distance_m, 0.1, 10.0);
  l.min_inlier_ratio = lc.number("min_inlier_ratio", l.min_inlier_ratio, 0.0, 1.0);
  l.max_rms_m = lc.number("max_rms_m", l.max_rms_m, 0.001, 1.0);
  l.max_residual_chi2 = lc.number("max_residual_chi2", l.max_residual_chi2, 0.1, 1e9);
  l.max_strain_chi2 = lc.number("max_strain_chi2", l.max_strain_chi2, 0.1, 1e9);
  l.prune_earlier_closures = lc.boolean("prune_earlier_closures", l.prune_earlier_closures);
  l.covariance_scale = lc.number("covariance_scale", l.covariance_scale, 1.0, 1e6);
  l.degenerate_variance_m2 = lc.number("degenerate_variance_m2", l.degenerate_variance_m2, 1e-4, 1e6);
  l.degenerate_keeps_graph_axis = lc.boolean("degenerate_keeps_graph_axis", l.degenerate_keeps_graph_axis);
  l.degenerate_covariance_scale = lc.number("degenerate_covariance_scale", l.degenerate_covariance_scale, 1.0, 1e6);
  l.point_spacing_m = lc.number("point_spacing_m", l.point_spacing_m, 0.0, 1.0);
  l.correlative = load_correlative(lc.section("correlative"), l.correlative);

  const auto opt = c.section("optimizer");
  o.optimizer.max_iterations = static_cast<int>(opt.integer("max_iterations", o.optimizer.max_iterations, 1, 1000));
  o.optimizer.robust_scale = opt.number("robust_scale", o.optimizer.robust_scale, 1e-3, 1e6);
  const auto kernel = opt.choice("kernel", "huber", {"huber", "cauchy"});
  o.optimizer.kernel = kernel == "huber" ? RobustKernel::kHuber : RobustKernel::kCauchy;

  const auto rep = c.section("republish");
  o.republish_min_change_m = rep.number("min_change_m", o.republish_min_change_m, 0.0, 10.0);
  o.republish_min_change_rad = rep.number("min_change_deg", o.republish_min_change_rad / kDeg, 0.0, 180.0) * kDeg;
  return o;
}

}  // namespace rgnav::scan_mapper
