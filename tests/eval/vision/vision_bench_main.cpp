// rgnav_vision_bench: the figures of ./rgnav bench vision that belong to the dense-stereo part.
//   aloe_*: the matcher (config/vision.yaml's SGBM settings at full scale, the disparity range
//     widened to the pair's) on the Middlebury Aloe pair against its ground truth (aloe_eval.h).
//   frames: the simulated head (drivers/sim stereo renderer, config/stereo/sim_b21r_head.yml,
//     image noise 2 grey levels, JPEG q90 as stereo_capture sends them) driven straight up to the
//     world's tables from the sides that are free, head tilted down; every frame through the vision
//     pipeline with the shipped config on one OpenCV thread, the odometry pose = the true pose.
//     frame_ms_*: JPEG decode of both images + rectify + SGBM + points + OctoMap insertion + column
//     projection (+ the 3D rectangles in every rectangles.every_frames-th frame, their p50 in
//     frame_stage_ms_p50.rectangles over the frames that ran them); wall-clock time.
//     frame_cpu_ms_p50/p90: the same frames in CPU time of the thread (what they cost one core,
//     whatever else the machine runs). octomap_points_per_s: points given to OctoMap's insertPointCloud per second of it.
//     grid_*: the grid of every frame against the cells holding rendered ground-truth points in the
//     height band (within max_range of the camera, all frames so far): false obstacles = occupied
//     cells with no such cell within one cell (_3_cells: within three, i.e. not just a surface
//     thickened by depth noise); missed = such cells with no occupied cell within one.
//     table_top_occupied_ratio: at the end of each approach, share of the cells under the table's
//     top (inset 5 cm, legs excluded) that are occupied.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iostream>
#include <set>

#include "aloe_eval.h"
#include "percentile.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "drivers/stereo/image_encoding.h"
#include "drivers/stereo/stereo_calibration.h"
#include "runtime/process_main.h"
#include "sim/stereo_renderer.h"
#include "sim/world_yaml.h"
#include "vision/rig_from_calibration.h"
#include "vision/vision_options.h"
#include "vision/vision_pipeline.h"

namespace {

using rgnav::bench::percentile;

using namespace rgnav;
using Clock = std::chrono::steady_clock;

// CPU time of the calling thread [ms].
double thread_cpu_ms()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Distance from p to an oriented rectangle (0 inside).
double rect_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& c, const Eigen::Vector2d& size, double yaw)
{
  const Eigen::Vector2d l = Eigen::Rotation2Dd(-yaw) * (p - c);
  const Eigen::Vector2d d = (l.cwiseAbs() - 0.5 * size).cwiseMax(0.0);
  return d.norm();
}

bool free_at(const sim::World& w, const Eigen::Vector2d& p, double clearance)
{
  for (const auto& wall : w.walls)
    if (segment_distance(p, wall.a, wall.b) < clearance) return false;
  for (const auto& d : w.doors)   // open or closed: the drive stays out of doorways
    if (segment_distance(p, d.hinge, d.latch) < clearance) return false;
  for (const auto& b : w.boxes)
    if (rect_distance(p, b.center, b.size, b.yaw) < clearance) return false;
  for (const auto& t : w.tables)
    if (rect_distance(p, t.center, t.size, t.yaw) < clearance) return false;
  return true;
}

bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p), d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

// No wall or door between the two points.
bool in_sight(const sim::World& w, const Eigen::Vector2d& p, const Eigen::Vector2d& q)
{
  for (const auto& wall : w.walls)
    if (segments_cross(p, q, wall.a, wall.b)) return false;
  for (const auto& d : w.doors)
    if (segments_cross(p, q, d.hinge, d.latch)) return false;
  return true;
}

struct Approach
{
  const sim::Table* table;
  Eigen::Vector2d from, to;
  double heading;
};

// Straight drives from 2.4 m to 0.6 m off the middle of a table side, facing it, clear of
// everything by 0.35 m.
std::vector<Approach> approaches(const sim::World& w, size_t max_count)
{
  std::vector<Approach> out;
  for (const auto& t : w.tables) {
    for (int side = 0; side < 4 && out.size() < max_count; ++side) {
      const double a = t.yaw + side * M_PI / 2;
      const Eigen::Vector2d n(std::cos(a), std::sin(a));
      const double half = 0.5 * ((side % 2 == 0) ? t.size.x() : t.size.y());
      const Eigen::Vector2d edge = t.center + half * n;
      Approach ap{&t, edge + 2.4 * n, edge + 0.6 * n, a + M_PI};
      bool ok = in_sight(w, ap.from, t.center);
      for (double s = 0; s <= 1.0 && ok; s += 0.05) ok = free_at(w, ap.from + s * (ap.to - ap.from), 0.35);
      if (ok) {
        out.push_back(ap);
        break;   // one approach per table: more tables, not more sides
      }
    }
    if (out.size() >= max_count) break;
  }
  return out;
}

using Cell = std::pair<int64_t, int64_t>;

struct GridScore
{
  long occupied = 0, false_obstacles = 0, false_far = 0, truth = 0, missed = 0;   // false_far: no truth within 3 cells
  long false_by_range[4] = {0, 0, 0, 0};   // false obstacles 0-1, 1-2, 2-3, 3+ m from the robot
  long occupied_by_range[4] = {0, 0, 0, 0};
};

void score(const vision::ObstacleGrid& g, const std::set<Cell>& truth, const Eigen::Vector2d& robot, GridScore* s)
{
  const double res = g.resolution;
  const int64_t ox = std::llround(g.odom_from_grid.x() / res), oy = std::llround(g.odom_from_grid.y() / res);
  const auto occupied_at = [&](int64_t cx, int64_t cy) {
    const int64_t x = cx - ox, y = cy - oy;
    return x >= 0 && y >= 0 && x < g.width && y < g.height && g.at(static_cast<int>(x), static_cast<int>(y)) >= 50;
  };
  const auto near = [](auto&& pred, int64_t cx, int64_t cy, int reach = 1) {
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx)
        if (pred(cx + dx, cy + dy)) return true;
    return false;
  };
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      if (g.at(x, y) < 50) continue;
      ++s->occupied;
      const Eigen::Vector2d c = g.odom_from_grid * Eigen::Vector2d((x + 0.5) * res, (y + 0.5) * res);
      const int bin = std::min(3, static_cast<int>((c - robot).norm()));
      ++s->occupied_by_range[bin];
      if (!near([&](int64_t a, int64_t b) { return truth.count({a, b}) > 0; }, ox + x, oy + y)) {
        ++s->false_obstacles;
        ++s->false_by_range[bin];
        if (!near([&](int64_t a, int64_t b) { return truth.count({a, b}) > 0; }, ox + x, oy + y, 3)) ++s->false_far;
      }
    }
  for (const auto& [cx, cy] : truth) {
    const int64_t x = cx - ox, y = cy - oy;
    if (x < 0 || y < 0 || x >= g.width || y >= g.height) continue;
    ++s->truth;
    if (!near(occupied_at, cx, cy)) ++s->missed;
  }
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"vision benchmark: Aloe disparity, and the pipeline on simulated frames"};
  std::string out_path, data_dir = runtime::default_data_dir(), world_arg = "office";
  int frames_per_approach = 20, max_approaches = 3;
  app.add_option("--out", out_path, "JSON output (default: stdout)");
  app.add_option("--data", data_dir, "the shared data folder (stereo/aloe)");
  app.add_option("--world", world_arg, "world name (config/worlds) or file with tables");
  app.add_option("--frames", frames_per_approach, "frames per approach");
  app.add_option("--approaches", max_approaches, "tables approached");
  std::string picture_dir;
  app.add_option("--pictures", picture_dir, "write each approach's last grid as a PNG here (white: occupied and true, "
                                             "red: occupied without truth, green: truth missed, grey: free)");
  CLI11_PARSE(app, argc, argv);
  cv::setNumThreads(1);   // one core, as the process runs
  nlohmann::json j;
  try {
    const std::string config_dir = runtime::default_config_dir();
    const std::string config_path = config_dir + "/vision.yaml";
    const auto cfg = config::Config::load(config_path);
    const auto robot = config::load_robot_description_file(config_dir + "/robot.yaml");
    const vision::VisionNodeOptions options = vision::load_vision_options(cfg, robot, config_path);

    // Aloe at full scale: the pair's disparities reach ~ a sixth of its width.
    vision::DisparityOptions aloe = options.vision.disparity;
    aloe.downscale = 1;
    aloe.num_disparities = 272;
    const double threshold = 1.0;
    const auto a = vision::eval::evaluate_aloe(data_dir + "/stereo/aloe", aloe, threshold);
    j["aloe_bad_pixel_ratio"] = a.bad_ratio;
    j["aloe_bad_pixel_threshold_px"] = a.threshold_px;
    j["aloe_bad_pixel_ratio_2px"] = a.bad_ratio_2px;
    j["aloe_bad_pixel_ratio_estimated"] = a.bad_ratio_estimated;
    j["aloe_density"] = a.density;
    j["aloe_gt_pixels"] = a.gt_pixels;
    j["aloe_gt_max_disparity_px"] = a.gt_max;
    j["aloe_scale_check"] = a.scale_check;
    j["aloe_match_ms"] = a.ms;
    j["aloe_size"] = {a.width, a.height};
    std::cerr << "aloe " << a.width << "x" << a.height << ": bad(" << threshold << " px) " << a.bad_ratio << ", bad(2 px) "
              << a.bad_ratio_2px << ", density " << a.density << ", scale " << a.scale_check << ", gt max " << a.gt_max
              << ", " << a.ms << " ms\n";

    // Frames of the simulated head.
    const auto calibration = stereo::load_stereo_calibration(options.calibration_file);
    const sim::World world = sim::load_world(sim::resolve_world_path(world_arg, config_dir + "/worlds"));
    sim::StereoRenderOptions ro;
    ro.noise_sigma = 2.0;
    const sim::StereoRenderer renderer(world, calibration, ro);
    const auto drives = approaches(world, static_cast<size_t>(max_approaches));
    if (drives.empty()) throw std::runtime_error(world.source + ": no table with a free approach");
    const double tilt = -0.35;
    const double res = options.vision.map.resolution;
    const cv::Matx33d K = calibration.M1;

    std::vector<double> frame_cpu_ms, rectangles_ms;
    std::vector<double> frame_ms, decode_ms, rectify_ms, disparity_ms, points_ms, map_ms, project_ms, points_per_frame;
    double insert_points = 0, insert_s = 0, memory_max = 0;
    std::vector<double> table_ratios;
    GridScore gs;
    uint64_t frame_no = 0;
    for (const Approach& ap : drives) {
      vision::VisionPipeline pipeline(vision::rig_from_calibration(calibration), options.vision);
      std::set<Cell> truth;
      vision::ObstacleGrid last;
      for (int i = 0; i < frames_per_approach; ++i) {
        const double s = frames_per_approach > 1 ? static_cast<double>(i) / (frames_per_approach - 1) : 1.0;
        const Eigen::Vector2d p = ap.from + s * (ap.to - ap.from);
        sim::HeadView view;
        view.robot = {p.x(), p.y(), ap.heading};
        view.tilt = tilt;
        view.frame = ++frame_no;
        const sim::StereoRender r = renderer.render(view);
        // Ground truth: rendered depth points in the band, within reach of the map.
        const Eigen::Isometry3d world_from_camera = renderer.world_from_left_camera(view);
        for (int v = 0; v < r.left.depth.rows; v += 3)
          for (int u = 0; u < r.left.depth.cols; u += 3) {
            const float z = r.left.depth.at<float>(v, u);
            if (!(z > 0.f) || z > options.vision.map.max_range) continue;
            const Eigen::Vector3d c((u - K(0, 2)) * z / K(0, 0), (v - K(1, 2)) * z / K(1, 1), z);
            const Eigen::Vector3d w = world_from_camera * c;
            if (w.z() < options.vision.map.min_height || w.z() > options.vision.map.max_height) continue;
            truth.insert({static_cast<int64_t>(std::floor(w.x() / res)), static_cast<int64_t>(std::floor(w.y() / res))});
          }
        const image_t left_msg = stereo::encode_image(r.left.image, 1, stereo::Encoding::kJpeg, 90);
        const image_t right_msg = stereo::encode_image(r.right.image, 1, stereo::Encoding::kJpeg, 90);
        const auto t0 = Clock::now();
        const double cpu0 = thread_cpu_ms();
        vision::StereoFrame f;
        f.left = *stereo::decode_image(left_msg);
        f.right = *stereo::decode_image(right_msg);
        const double dec = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        f.utime = static_cast<int64_t>(frame_no) * 100'000;
        f.tilt = tilt;
        f.odom_from_base = geometry::Pose2(p.x(), p.y(), ap.heading);
        const vision::FrameResult fr = pipeline.process(f);
        frame_cpu_ms.push_back(thread_cpu_ms() - cpu0);
        if (fr.rectangles_run) rectangles_ms.push_back(fr.rectangles_ms);
        frame_ms.push_back(dec + fr.total_ms);
        decode_ms.push_back(dec);
        rectify_ms.push_back(fr.rectify_ms);
        disparity_ms.push_back(fr.disparity_ms);
        points_ms.push_back(fr.points_ms);
        map_ms.push_back(fr.map_ms);
        project_ms.push_back(fr.project_ms);
        points_per_frame.push_back(static_cast<double>(fr.points));
        insert_points += static_cast<double>(fr.insert.points);
        insert_s += fr.insert.seconds;
        memory_max = std::max(memory_max, static_cast<double>(pipeline.map().memory_bytes()) / 1e6);
        score(fr.grid, truth, p, &gs);
        last = fr.grid;
      }
      if (!picture_dir.empty()) {
        cv::Mat img(last.height, last.width, CV_8UC3, cv::Scalar(60, 0, 0));
        const int64_t ox = std::llround(last.odom_from_grid.x() / res), oy = std::llround(last.odom_from_grid.y() / res);
        for (int y = 0; y < last.height; ++y)
          for (int x = 0; x < last.width; ++x) {
            const int8_t c = last.at(x, y);
            const bool t = truth.count({ox + x, oy + y}) > 0;
            cv::Vec3b& px = img.at<cv::Vec3b>(last.height - 1 - y, x);
            if (c >= 50) px = t ? cv::Vec3b(255, 255, 255) : cv::Vec3b(0, 0, 255);
            else if (t) px = cv::Vec3b(0, 255, 0);
            else if (c >= 0) px = cv::Vec3b(120, 120, 120);
          }
        cv::resize(img, img, cv::Size(), 4, 4, cv::INTER_NEAREST);
        cv::imwrite(picture_dir + "/" + ap.table->name + ".png", img);
      }
      // The table's top at the end of the approach.
      const sim::Table& t = *ap.table;
      long top = 0, top_occupied = 0;
      for (int y = 0; y < last.height; ++y)
        for (int x = 0; x < last.width; ++x) {
          const Eigen::Vector2d c = last.odom_from_grid * Eigen::Vector2d((x + 0.5) * res, (y + 0.5) * res);
          const Eigen::Vector2d l = Eigen::Rotation2Dd(-t.yaw) * (c - t.center);
          if (std::abs(l.x()) > 0.5 * t.size.x() - 0.05 || std::abs(l.y()) > 0.5 * t.size.y() - 0.05) continue;
          // Legs (inset by their size from the corners) are seen by the laser anyway.
          if (std::abs(l.x()) > 0.5 * t.size.x() - 2.5 * t.leg_size && std::abs(l.y()) > 0.5 * t.size.y() - 2.5 * t.leg_size) continue;
          ++top;
          if (last.at(x, y) >= 50) ++top_occupied;
        }
      const double ratio = top > 0 ? static_cast<double>(top_occupied) / top : 0.0;
      table_ratios.push_back(ratio);
      std::cerr << "approach to " << t.name << " from (" << ap.from.x() << ", " << ap.from.y() << "): top cells occupied "
                << top_occupied << "/" << top << "\n";
    }
    j["world"] = world.name;
    j["frames"] = frame_ms.size();
    j["frame_ms_p50"] = percentile(frame_ms, 0.5);
    j["frame_ms_p90"] = percentile(frame_ms, 0.9);
    j["frame_cpu_ms_p50"] = percentile(frame_cpu_ms, 0.5);
    j["frame_cpu_ms_p90"] = percentile(frame_cpu_ms, 0.9);
    j["frame_stage_ms_p50"] = {{"jpeg_decode", percentile(decode_ms, 0.5)},  {"rectify", percentile(rectify_ms, 0.5)},
                               {"sgbm", percentile(disparity_ms, 0.5)},      {"points", percentile(points_ms, 0.5)},
                               {"octomap_insert", percentile(map_ms, 0.5)},  {"column_projection", percentile(project_ms, 0.5)},
                               {"rectangles", rectangles_ms.empty() ? 0.0 : percentile(rectangles_ms, 0.5)}};
    j["points_per_frame_p50"] = percentile(points_per_frame, 0.5);
    j["octomap_points_per_s"] = insert_s > 0 ? insert_points / insert_s : 0.0;
    j["map_memory_mb_max"] = memory_max;
    j["grid_false_obstacle_ratio"] = gs.occupied > 0 ? static_cast<double>(gs.false_obstacles) / gs.occupied : 0.0;
    j["grid_missed_obstacle_ratio"] = gs.truth > 0 ? static_cast<double>(gs.missed) / gs.truth : 0.0;
    j["grid_false_obstacle_ratio_3_cells"] = gs.occupied > 0 ? static_cast<double>(gs.false_far) / gs.occupied : 0.0;
    std::vector<double> by_range;
    for (int b = 0; b < 4; ++b)
      by_range.push_back(gs.occupied_by_range[b] > 0 ? static_cast<double>(gs.false_by_range[b]) / gs.occupied_by_range[b] : 0.0);
    j["grid_false_obstacle_ratio_by_range_m"] = {{"0-1", by_range[0]}, {"1-2", by_range[1]}, {"2-3", by_range[2]}, {"3+", by_range[3]}};
    j["table_approaches"] = table_ratios.size();
    j["table_top_occupied_ratio"] = table_ratios.empty() ? 0.0 : percentile(table_ratios, 0.0);
    j["table_top_occupied_ratio_each"] = table_ratios;
    j["opencv_threads"] = 1;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_vision_bench: " << e.what() << "\n";
    return 1;
  }
  const std::string text = j.dump(2) + "\n";
  if (out_path.empty()) std::cout << text;
  else std::ofstream(out_path) << text;
  return 0;
}
