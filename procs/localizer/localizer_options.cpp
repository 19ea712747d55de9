#include "localizer/localizer_options.h"

#include "config/config.h"
#include "config/robot_description.h"

namespace rgnav::localizer {

LocalizerNodeOptions load_localizer_options(const config::Config& root, const config::RobotDescription& robot)
{
  LocalizerNodeOptions o;
  const auto ch = root.section("channels");
  auto& c = o.channels;
  c.rg_map = ch.string("rg_map", c.rg_map);
  c.laser = ch.string("laser", c.laser);
  c.odometry = ch.string("odometry", c.odometry);
  c.request = ch.string("request", c.request);
  c.pose = ch.string("pose", c.pose);
  c.gateway_passed = ch.string("gateway_passed", c.gateway_passed);

  const auto cfg = root.section("localizer");
  auto& l = o.localizer;
  l.base_from_laser = robot.laser_front.base_from_laser;
  l.update_distance = cfg.number("update_distance_m", l.update_distance, 0.0, 2.0);
  l.update_angle_deg = cfg.number("update_angle_deg", l.update_angle_deg, 0.0, 90.0);
  l.handover_reach = cfg.number("handover_reach_m", l.handover_reach, 0.1, 10.0);
  l.handover_bbox_margin = cfg.number("handover_bbox_margin_m", l.handover_bbox_margin, 0.0, 10.0);
  l.gateway_passed_distance = cfg.number("gateway_passed_distance_m", l.gateway_passed_distance, 0.0, 5.0);
  l.initial_xy = cfg.number("initial_xy_m", l.initial_xy, 0.0, 5.0);
  l.initial_theta_deg = cfg.number("initial_theta_deg", l.initial_theta_deg, 0.0, 180.0);
  l.resume_xy = cfg.number("resume_xy_m", l.resume_xy, 0.0, 5.0);
  l.resume_theta_deg = cfg.number("resume_theta_deg", l.resume_theta_deg, 0.0, 180.0);
  l.resume_give_up_updates = static_cast<int>(cfg.integer("resume_give_up_updates", l.resume_give_up_updates, 1, 1000));
  l.seed = static_cast<uint64_t>(cfg.integer("seed", static_cast<int64_t>(l.seed), 0, 1'000'000'000));
  o.max_scan_age = cfg.number("max_scan_age_s", o.max_scan_age, 0.01, 10.0);
  o.persist_period = cfg.number("persist_period_s", o.persist_period, 0.1, 600.0);

  const auto mo = root.section("motion_noise");
  auto& m = l.motion;
  m.translation_per_m = mo.number("translation_per_m", m.translation_per_m, 0.0, 1.0);
  m.translation_per_sqrt_m = mo.number("translation_per_sqrt_m", m.translation_per_sqrt_m, 0.0, 1.0);
  m.rotation_per_rad = mo.number("rotation_per_rad", m.rotation_per_rad, 0.0, 1.0);
  m.rotation_per_sqrt_rad = mo.number("rotation_per_sqrt_rad", m.rotation_per_sqrt_rad, 0.0, 1.0);
  m.rotation_per_m = mo.number("rotation_per_m", m.rotation_per_m, 0.0, 1.0);
  m.rotation_per_sqrt_m = mo.number("rotation_per_sqrt_m", m.rotation_per_sqrt_m, 0.0, 1.0);
  m.lateral_per_m = mo.number("lateral_per_m", m.lateral_per_m, 0.0, 1.0);

  const auto sc = root.section("scan_model");
  auto& s = l.scan;
  s.beams = static_cast<int>(sc.integer("beams", s.beams, 5, 1000));
  s.min_range = sc.number("min_range_m", s.min_range, 0.0, 5.0);
  s.sigma = sc.number("sigma_m", s.sigma, 0.005, 2.0);
  s.z_hit = sc.number("z_hit", s.z_hit, 0.0, 1.0);
  s.z_rand = sc.number("z_rand", s.z_rand, 1e-6, 1.0);
  s.max_distance = sc.number("max_distance_m", s.max_distance, 0.05, 10.0);
  s.field_resolution = sc.number("field_resolution_m", s.field_resolution, 0.005, 0.5);
  s.field_margin = sc.number("field_margin_m", s.field_margin, 0.0, 10.0);
  s.beam_weight = sc.number("beam_weight", s.beam_weight, 0.001, 1.0);
  s.inlier_distance = sc.number("inlier_distance_m", s.inlier_distance, 0.01, 2.0);

  const auto pc = root.section("particles");
  auto& n = l.count;
  n.min = static_cast<int>(pc.integer("min", n.min, 10, 1'000'000));
  n.max = static_cast<int>(pc.integer("max", n.max, n.min, 1'000'000));
  n.kld_epsilon = pc.number("kld_epsilon", n.kld_epsilon, 0.001, 1.0);
  n.kld_z = pc.number("kld_z", n.kld_z, 0.0, 10.0);
  n.bin_xy = pc.number("bin_xy_m", n.bin_xy, 0.01, 5.0);
  n.bin_theta_deg = pc.number("bin_theta_deg", n.bin_theta_deg, 0.5, 180.0);
  n.resample_ess_ratio = pc.number("resample_ess_ratio", n.resample_ess_ratio, 0.0, 1.0);

  const auto gl = root.section("global");
  auto& g = l.global;
  g.cell = gl.number("cell_m", g.cell, 0.05, 5.0);
  g.headings = static_cast<int>(gl.integer("headings", g.headings, 1, 720));
  g.beams = static_cast<int>(gl.integer("beams", g.beams, 5, 1000));
  g.sigma = gl.number("sigma_m", g.sigma, 0.01, 2.0);
  g.hypotheses = static_cast<int>(gl.integer("hypotheses", g.hypotheses, 1, 100'000));
  g.particles = static_cast<int>(gl.integer("particles", g.particles, 10, 1'000'000));
  g.seed_xy = gl.number("seed_xy_m", g.seed_xy, 0.0, 2.0);
  g.seed_theta_deg = gl.number("seed_theta_deg", g.seed_theta_deg, 0.0, 90.0);
  g.reseed_share = gl.number("reseed_share", g.reseed_share, 0.0, 1.0);
  g.beam_weight = gl.number("beam_weight", g.beam_weight, 0.001, 1.0);
  g.min_travel = gl.number("min_travel_m", g.min_travel, 0.0, 100.0);
  g.unique_distance = gl.number("unique_distance_m", g.unique_distance, 0.1, 100.0);
  g.unique_margin = gl.number("unique_margin", g.unique_margin, 0.0, 1000.0);
  g.rivals = static_cast<int>(gl.integer("rivals", g.rivals, 1, 1000));
  g.view_spacing = gl.number("view_spacing_m", g.view_spacing, 0.0, 10.0);
  g.view_path_length = gl.number("view_path_length_m", g.view_path_length, 0.0, 100.0);
  g.claim_path_search = gl.boolean("claim_path_search", g.claim_path_search);
  g.claim_judged_beams = gl.boolean("claim_judged_beams", g.claim_judged_beams);
  g.judged_through_gateways = gl.boolean("judged_through_gateways", g.judged_through_gateways);
  g.path_search_places = static_cast<int>(gl.integer("path_search_places", g.path_search_places, 1, 1000));

  const auto re = root.section("recovery");
  auto& r = l.recovery;
  r.alpha_slow = re.number("alpha_slow", r.alpha_slow, 0.0, 1.0);
  r.alpha_fast = re.number("alpha_fast", r.alpha_fast, 0.0, 1.0);
  r.max_share = re.number("max_share", r.max_share, 0.0, 1.0);
  r.kidnap_inlier_ratio = re.number("kidnap_inlier_ratio", r.kidnap_inlier_ratio, 0.0, 1.0);
  r.kidnap_after_s = re.number("kidnap_after_s", r.kidnap_after_s, 0.0, 60.0);
  r.kidnap_drop = re.number("kidnap_drop", r.kidnap_drop, 0.0, 1.0);
  r.kidnap_jump = re.number("kidnap_jump_m", r.kidnap_jump, 0.1, 100.0);
  r.usual_alpha = re.number("usual_alpha", r.usual_alpha, 0.0, 1.0);

  const auto es = root.section("estimate");
  auto& e = l.estimate;
  e.cluster_xy = es.number("cluster_xy_m", e.cluster_xy, 0.01, 10.0);
  e.cluster_theta_deg = es.number("cluster_theta_deg", e.cluster_theta_deg, 0.1, 180.0);
  e.converged_xy = es.number("converged_xy_m", e.converged_xy, 0.001, 10.0);
  e.converged_theta_deg = es.number("converged_theta_deg", e.converged_theta_deg, 0.01, 180.0);
  e.min_cluster_share = es.number("min_cluster_share", e.min_cluster_share, 0.0, 1.0);
  return o;
}

}  // namespace rgnav::localizer
