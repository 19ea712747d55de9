#include "vision/vision_options.h"

#include <algorithm>
#include <filesystem>

#include "config/config.h"
#include "config/robot_description.h"

namespace rgnav::vision {

VisionNodeOptions load_vision_options(const config::Config& root, const config::RobotDescription& robot,
                                      const std::string& config_path)
{
  VisionNodeOptions o;
  const auto ch = root.section("channels");
  auto& c = o.channels;
  c.stereo = ch.string("stereo", c.stereo);
  c.odometry = ch.string("odometry", c.odometry);
  c.laser = ch.string("laser", c.laser);
  c.obstacles = ch.string("obstacles", c.obstacles);
  c.objects = ch.string("objects", c.objects);

  const auto vi = root.section("vision");
  o.calibration_id = vi.string("calibration_id", o.calibration_id);
  if (o.calibration_id.empty() || o.calibration_id.find_first_of("/\\") != std::string::npos)
    vi.fail("calibration_id", "must be a plain name (the file config/stereo/<calibration_id>.yml)");
  std::filesystem::path file = vi.string("calibration_file", "stereo/" + o.calibration_id + ".yml");
  if (file.is_relative()) file = std::filesystem::path(config_path).parent_path() / file;
  o.calibration_file = file.lexically_normal().string();
  o.max_pose_gap = vi.number("max_pose_gap_s", o.max_pose_gap, 0.01, 2.0);
  o.laser_period = vi.number("laser_period_s", o.laser_period, 0.0, 10.0);
  o.frame_queue = static_cast<int>(vi.integer("frame_queue", o.frame_queue, 1, 30));
  o.opencv_threads = static_cast<int>(vi.integer("opencv_threads", o.opencv_threads, 1, 64));
  o.stale_after = vi.number("stale_after_s", o.stale_after, 0.1, 60.0);
  o.vision.rectify_alpha = vi.number("rectify_alpha", o.vision.rectify_alpha, -1.0, 1.0);

  const auto di = root.section("disparity");
  auto& d = o.vision.disparity;
  d.downscale = static_cast<int>(di.integer("downscale", d.downscale, 1, 4));
  if (d.downscale == 3) di.fail("downscale", "must be 1, 2 or 4");
  d.min_disparity = static_cast<int>(di.integer("min_disparity", d.min_disparity, 0, 256));
  d.num_disparities = static_cast<int>(di.integer("num_disparities", d.num_disparities, 16, 512));
  if (d.num_disparities % 16 != 0) di.fail("num_disparities", "must be a multiple of 16");
  d.block_size = static_cast<int>(di.integer("block_size", d.block_size, 1, 31));
  if (d.block_size % 2 == 0) di.fail("block_size", "must be odd");
  d.p1 = static_cast<int>(di.integer("p1", d.p1, 0, 100000));
  d.p2 = static_cast<int>(di.integer("p2", d.p2, 0, 100000));
  if (d.p1 > 0 && d.p2 > 0 && d.p2 <= d.p1) di.fail("p2", "must be greater than p1");
  d.disp12_max_diff = static_cast<int>(di.integer("disp12_max_diff", d.disp12_max_diff, -1, 64));
  d.pre_filter_cap = static_cast<int>(di.integer("pre_filter_cap", d.pre_filter_cap, 1, 63));
  d.uniqueness_ratio = static_cast<int>(di.integer("uniqueness_ratio", d.uniqueness_ratio, 0, 100));
  d.speckle_window_size = static_cast<int>(di.integer("speckle_window_size", d.speckle_window_size, 0, 10000));
  d.speckle_range = static_cast<int>(di.integer("speckle_range", d.speckle_range, 0, 64));
  d.mode = di.choice("mode", d.mode, {"sgbm", "hh", "sgbm_3way", "hh4"});
  d.pad_left = di.boolean("pad_left", d.pad_left);

  const auto pt = root.section("points");
  auto& p = o.vision.points;
  p.stride = static_cast<int>(pt.integer("stride", p.stride, 1, 16));
  p.min_depth = pt.number("min_depth_m", p.min_depth, 0.05, 10.0);
  p.max_depth = pt.number("max_depth_m", p.max_depth, p.min_depth, 100.0);

  const auto re = root.section("rectangles");
  auto& r = o.vision.rectangles;
  r.enabled = re.boolean("enabled", r.enabled) && !c.objects.empty();
  r.every_frames = static_cast<int>(re.integer("every_frames", r.every_frames, 1, 1000));
  auto& q = r.detector.quadrangles;
  q.min_length_px = re.number("min_line_px", q.min_length_px, 2.0, 1000.0);
  q.dn_max_px = re.number("dn_max_px", q.dn_max_px, 1.0, 200.0);
  q.do_min_px = re.number("do_min_px", q.do_min_px, 1.0, 500.0);
  r.detector.plane_tolerance_px = re.number("plane_tolerance_px", r.detector.plane_tolerance_px, 0.1, 10.0);
  r.detector.min_support = re.number("min_support", r.detector.min_support, 0.0, 1.0);
  r.detector.min_side_m = re.number("min_side_m", r.detector.min_side_m, 0.01, 10.0);
  r.detector.max_side_m = re.number("max_side_m", r.detector.max_side_m, r.detector.min_side_m, 20.0);
  r.detector.refine.sigma_px = re.number("corner_sigma_px", r.detector.refine.sigma_px, 0.05, 10.0);
  r.detector.refine.sigma_disparity = re.number("disparity_sigma_px", r.detector.refine.sigma_disparity, 0.01, 10.0);

  const auto mp = root.section("map");
  auto& m = o.vision.map;
  m.resolution = mp.number("resolution_m", m.resolution, 0.01, 0.5);
  m.max_range = mp.number("max_range_m", m.max_range, 0.5, 30.0);
  m.stereo_prob_hit = mp.number("stereo_prob_hit", m.stereo_prob_hit, 0.51, 0.99);
  m.stereo_prob_miss = mp.number("stereo_prob_miss", m.stereo_prob_miss, 0.01, 0.49);
  m.laser_prob_hit = mp.number("laser_prob_hit", m.laser_prob_hit, 0.51, 0.99);
  m.laser_prob_miss = mp.number("laser_prob_miss", m.laser_prob_miss, 0.01, 0.49);
  m.clamp_min = mp.number("clamp_min", m.clamp_min, 0.001, 0.49);
  m.clamp_max = mp.number("clamp_max", m.clamp_max, 0.51, 0.999);
  m.stereo_sigma = mp.number("stereo_sigma", m.stereo_sigma, 0.001, 10.0);
  m.laser_sigma = mp.number("laser_sigma", m.laser_sigma, 0.001, 10.0);
  m.laser_only_obstacles = mp.boolean("laser_only_obstacles", m.laser_only_obstacles);
  m.laser_max_range = mp.number("laser_max_range_m", m.laser_max_range, 0.5, 80.0);
  m.floor_tolerance = mp.number("floor_tolerance_m", m.floor_tolerance, 0.0, 0.5);
  m.disparity_sigma = mp.number("disparity_sigma_px", m.disparity_sigma, 0.0, 10.0);
  m.max_floor_tolerance = mp.number("max_floor_tolerance_m", m.max_floor_tolerance, m.floor_tolerance, 1.0);
  m.drop_off_depth = mp.number("drop_off_depth_m", m.drop_off_depth, m.floor_tolerance, 2.0);
  m.min_height = mp.number("min_height_m", m.min_height, m.floor_tolerance, 2.0);
  m.max_height = mp.number("max_height_m", robot.height + 0.1, m.min_height + m.resolution, 5.0);
  m.max_point_height = mp.number("max_point_height_m", m.max_point_height, m.max_height, 10.0);
  m.forget_in_view_after = mp.number("forget_in_view_after_s", m.forget_in_view_after, 0.0, 3600.0);
  m.laser_clears_stereo = mp.boolean("laser_clears_stereo", m.laser_clears_stereo);
  m.keep_radius = mp.number("keep_radius_m", m.keep_radius, 1.0, 50.0);
  m.trim_distance = mp.number("trim_distance_m", m.trim_distance, 0.05, 10.0);
  // OctoMap's keys reach 2^15 voxels either side of the anchor.
  const double key_reach = 0.9 * 32768.0 * m.resolution - m.keep_radius;
  m.reanchor_distance = mp.number("reanchor_distance_m", std::min(m.reanchor_distance, key_reach), 2.0 * m.keep_radius,
                                  std::max(key_reach, 2.0 * m.keep_radius));
  m.grid_size = mp.number("grid_size_m", m.grid_size, 1.0, 2.0 * m.keep_radius);
  m.laser_height = robot.laser_front.height;
  o.base_from_laser = robot.laser_front.base_from_laser;
  return o;
}

}  // namespace rgnav::vision
