#include "gateway_detector/options.h"

#include <filesystem>

namespace rgnav::gateway_detector {

DetectorOptions load_detector_options(const config::Config& cfg, const config::RobotDescription& robot)
{
  DetectorOptions o;
  {
    const auto s = cfg.section("features");
    auto& f = o.features;
    f.cluster_gap = s.number("cluster_gap_m", f.cluster_gap, 0.01, 2.0);
    f.split_distance = s.number("split_distance_m", f.split_distance, 0.005, 0.5);
    f.min_segment_points = static_cast<int>(s.integer("min_segment_points", f.min_segment_points, 2, 100));
    f.min_segment_length = s.number("min_segment_length_m", f.min_segment_length, 0.0, 5.0);
    f.virtual_line_angle = s.number("virtual_line_angle_rad", f.virtual_line_angle, 0.0, 0.5);
    f.virtual_line_distance = s.number("virtual_line_distance_m", f.virtual_line_distance, 0.0, 1.0);
    f.depth_jump = s.number("depth_jump_m", f.depth_jump, 0.05, 5.0);
  }
  {
    const auto s = cfg.section("crossings");
    o.detect_crossings = s.boolean("enabled", o.detect_crossings);
    const double dhw = s.number("hallway_width_m", 2.0, 0.5, 10.0);
    auto& v = o.vlm;
    v.hallway_width = dhw;
    v.parallel_angle = s.number("parallel_angle_rad", v.parallel_angle, 0.0, 0.5);
    v.right_angle_tolerance = s.number("right_angle_tolerance_rad", v.right_angle_tolerance, 0.0, 0.8);
    v.width_min_factor = s.number("width_min_factor", v.width_min_factor, 0.1, 1.0);
    v.width_max_factor = s.number("width_max_factor", v.width_max_factor, 1.0, 5.0);
    v.min_side_support = s.number("min_side_support_m", v.min_side_support, 0.0, 10.0);
    v.min_front_support = s.number("min_front_support_m", v.min_front_support, 0.0, 10.0);
    v.max_front_distance = s.number("max_front_distance_m", v.max_front_distance, 1.0, 80.0);
    v.singularity_line_distance = s.number("singularity_line_distance_m", v.singularity_line_distance, 0.0, 2.0);
    v.min_depth_factor = s.number("min_depth_factor", v.min_depth_factor, 0.0, 1.0);
    v.max_depth_factor = s.number("max_depth_factor", v.max_depth_factor, 1.0, 5.0);
    v.duplicate_distance = s.number("duplicate_distance_m", v.duplicate_distance, 0.0, 1.0);
    v.max_hypotheses = static_cast<int>(s.integer("max_hypotheses", v.max_hypotheses, 1, 1000));
    auto& m = o.measures;
    m.hallway_width = dhw;
    m.on_line_low = s.number("on_line_low_m", m.on_line_low, -2.0, 0.0);
    m.on_line_high = s.number("on_line_high_m", m.on_line_high, 0.0, 2.0);
    m.over_line_setback = s.number("over_line_setback_m", m.over_line_setback, 0.0, 5.0);
    m.f_vlm = s.number("f_vlm", m.f_vlm, 0.0, 100.0);
    m.f_gw = s.number("f_gw", m.f_gw, 0.0, 100.0);
    m.exclude_occluded = s.boolean("exclude_occluded", m.exclude_occluded);
    m.min_visible_beams = static_cast<int>(s.integer("min_visible_beams", m.min_visible_beams, 1, 1000));
  }
  {
    const auto s = cfg.section("narrow_passages");
    auto& n = o.narrow_passages;
    o.detect_narrow_passages = s.boolean("enabled", o.detect_narrow_passages);
    n.viewing_directions = s.numbers("viewing_directions_rad", n.viewing_directions, -M_PI, M_PI, 1, 16);
    n.half_range = s.number("half_range_rad", n.half_range, 0.1, M_PI);
    n.max_distance = s.number("max_distance_m", n.max_distance, 0.2, 20.0);
    n.robot_radius = robot.radius;
    n.safety_distance = s.number("safety_distance_m", n.safety_distance, 0.0, 1.0);
    n.min_width = s.number("min_width_m", n.min_width, 0.1, 5.0);
    n.max_width = s.number("max_width_m", n.max_width, 0.1, 10.0);
    n.min_aperture = s.number("min_aperture_rad", n.min_aperture, 0.0, M_PI);
    n.max_aperture = s.number("max_aperture_rad", n.max_aperture, 0.0, 2 * M_PI);
    n.min_depth_behind = s.number("min_depth_behind_m", n.min_depth_behind, 0.0, 10.0);
    n.min_jamb_extent = s.number("min_jamb_extent_m", n.min_jamb_extent, 0.0, 5.0);
    n.jamb_link_distance = s.number("jamb_link_distance_m", n.jamb_link_distance, 0.01, 1.0);
    n.wall_gaps = s.boolean("wall_gaps", n.wall_gaps);
    n.wall_gap_max_distance = s.number("wall_gap_max_distance_m", n.wall_gap_max_distance, 0.2, 20.0);
    n.wall_gap_min_through = s.number("wall_gap_min_through", n.wall_gap_min_through, 0.0, 1.0);
    if (n.max_width < n.min_width) s.fail("max_width_m", "must be >= min_width_m");
    if (n.max_aperture < n.min_aperture) s.fail("max_aperture_rad", "must be >= min_aperture_rad");
  }
  {
    const auto s = cfg.section("doors");
    auto& d = o.doors;
    d.min_width = s.number("min_width_m", d.min_width, 0.1, 5.0);
    d.max_width = s.number("max_width_m", d.max_width, 0.1, 10.0);
    d.min_height = s.number("min_height_m", d.min_height, 0.5, 5.0);
    d.max_height = s.number("max_height_m", d.max_height, 0.5, 10.0);
    d.max_normal_z = s.number("max_normal_z", d.max_normal_z, 0.0, 1.0);
    d.match_distance = s.number("match_distance_m", d.match_distance, 0.01, 2.0);
    d.memory_s = s.number("memory_s", d.memory_s, 0.0, 3600.0);
    if (d.max_width < d.min_width) s.fail("max_width_m", "must be >= min_width_m");
    if (d.max_height < d.min_height) s.fail("max_height_m", "must be >= min_height_m");
  }
  {
    const auto s = cfg.section("tracking");
    auto& t = o.tracking;
    t.crossing_match_distance = s.number("crossing_match_distance_m", t.crossing_match_distance, 0.01, 5.0);
    t.passage_match_distance = s.number("passage_match_distance_m", t.passage_match_distance, 0.01, 5.0);
    t.group_distance = s.number("group_distance_m", t.group_distance, 0.0, 10.0);
    t.sequence_start_distance = s.number("sequence_start_distance_m", t.sequence_start_distance, 0.5, 50.0);
    t.sequence_end_distance = s.number("sequence_end_distance_m", t.sequence_end_distance, 0.0, 10.0);
    t.observation_spacing = s.number("observation_spacing_m", t.observation_spacing, 0.0, 5.0);
    t.max_missed = static_cast<int>(s.integer("max_missed_scans", t.max_missed, 0, 1000));
    t.hold_distance = s.number("hold_distance_m", t.hold_distance, 0.0, 10.0);
    t.lost_travel = s.number("lost_travel_m", t.lost_travel, 0.0, 10.0);
    t.max_missed_stationary = static_cast<int>(s.integer("max_missed_scans_stationary", t.max_missed_stationary, 0, 100000));
    t.min_observations = static_cast<int>(s.integer("min_observations", t.min_observations, 1, 1000));
    t.enter_distance = s.number("enter_distance_m", t.enter_distance, 0.01, 5.0);
    t.exit_margin = s.number("exit_margin_m", t.exit_margin, 0.0, 5.0);
    if (t.sequence_end_distance >= t.sequence_start_distance)
      s.fail("sequence_end_distance_m", "must be below sequence_start_distance_m");
  }
  return o;
}

HmmTrainingOptions load_training_options(const config::Config& s)
{
  HmmTrainingOptions o;
  o.clusters = static_cast<int>(s.integer("clusters", o.clusters, 1, 64));
  o.window_overlap = s.number("window_overlap", o.window_overlap, 0.0, 0.95);
  o.kmeans_iterations = static_cast<int>(s.integer("kmeans_iterations", o.kmeans_iterations, 1, 10000));
  o.min_cluster_size = static_cast<int>(s.integer("min_cluster_size", o.min_cluster_size, 1, 100000));
  o.state_distance_gap = s.number("state_distance_gap_m", o.state_distance_gap, 0.0, 20.0);
  o.noise_sigma = s.number("noise_sigma", o.noise_sigma, 1e-4, 1.0);
  o.em_iterations = static_cast<int>(s.integer("em_iterations", o.em_iterations, 0, 10000));
  o.em_tolerance = s.number("em_tolerance", o.em_tolerance, 0.0, 1.0);
  o.probability_floor = s.number("probability_floor", o.probability_floor, 0.0, 0.1);
  return o;
}

ClassifierConfig load_classifier_config(const config::Config& s, const std::string& config_path)
{
  ClassifierConfig c;
  c.models_path = s.string("models", "");
  c.require_models = s.boolean("require_models", false);
  if (!c.models_path.empty() && std::filesystem::path(c.models_path).is_relative())
    c.models_path = (std::filesystem::path(config_path).parent_path() / c.models_path).string();
  return c;
}

}  // namespace rgnav::gateway_detector
