// rgnav_vision_courses: obstacle courses in furnished rooms (furnished_course.h: tables whose tops
// the laser misses, pedestal chairs, wall shelves) driven by collision avoidance and the lld around
// the simulated B21r (tests/eval/control course_drive.h, the control bench's loop), each course twice
// in the same run: vision off (collision avoidance has the laser only) and vision on (the simulated
// head rendered in lock-step at stereo_capture's rate, the vision library's OBSTACLES_3D grid fed to
// collision avoidance as its node does: head_in_the_loop.h). A collision is the simulator's: the
// robot's body (config/robot.yaml's radius, from 2 cm above the floor to its height) meeting any
// solid in that band, table tops, seats and shelves included; the simulator stops the robot there.
//   courses, collisions_vision_off, collisions_vision_on: contacts over all courses;
//   courses_collided_vision_off/on: courses with at least one; reached_vision_off/on: goals reached
//   within the time limit; with_what_*: what was hit (table top, leg, seat, shelf, wall);
//   per_course[].vision_on_contacts_in_grid: for each contact with vision on, what the grids
//   delivered to collision avoidance had shown of the solid hit (head_in_the_loop.h ContactView:
//   grids_marking 0 = the vision never put it in the grid).
// The configs are the shipped ones (robot, lld, collision_avoidance, vision, stereo_capture_sim);
// the vision's 3D rectangles are off here (they do not touch the grid and cost about as much again).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <fstream>
#include <iostream>
#include <map>
#include <random>

#include "collision_avoidance/ca_options.h"
#include "config/config.h"
#include "config/robot_description.h"
#include "drivers/stereo/stereo_calibration.h"
#include "drivers/stereo/stereo_capture_node.h"
#include "lld/lld_options.h"
#include "runtime/process_main.h"
#include "sim/world_yaml.h"
#include "vision/vision_options.h"

#include "course_drive.h"
#include "furnished_course.h"
#include "head_in_the_loop.h"
#include "office_tour.h"
#include "percentile.h"

using namespace rgnav;

namespace {

// "table3.top" -> "table top", "chair0.seat" -> "chair seat", "wall[2]" -> "wall".
std::string what(const std::string& with)
{
  const auto dot = with.find('.');
  std::string kind = with.substr(0, with.find_first_of("0123456789[."));
  return dot == std::string::npos ? kind : kind + " " + with.substr(dot + 1);
}

struct ModeTotals
{
  int64_t collisions = 0;
  int collided = 0, reached = 0;
  double time_sum = 0.0;
  std::map<std::string, int> with;
  nlohmann::json add(const bench::CourseDriveResult& r)
  {
    collisions += r.collisions;
    collided += r.collisions > 0 ? 1 : 0;
    if (r.arrived) {
      ++reached;
      time_sum += r.time_s;
    }
    nlohmann::json hits = nlohmann::json::array();
    for (const auto& c : r.contacts) {
      const std::string w = what(c.value("with", std::string("?")));
      ++with[w];
      hits.push_back(w);
    }
    return {{"reached", r.arrived}, {"time_s", r.time_s}, {"collisions", r.collisions}, {"hit", hits},
            {"end", {r.end.x, r.end.y}}, {"mode", r.mode}};
  }
};

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"obstacle courses in furnished rooms, vision off and on"};
  std::string out_path, world_dir;
  std::string config_dir = runtime::default_config_dir();
  int ncourses = 50, only = -1, parts = 1, part = 0;
  uint64_t seed = 1;
  double latency = 0.15, time_limit = 120.0;
  app.add_option("--out", out_path, "JSON output (default: stdout)");
  app.add_option("--config-dir", config_dir);
  app.add_option("--courses", ncourses, "courses drawn (each driven twice)");
  app.add_option("--seed", seed);
  app.add_option("--only", only, "drive only this course (debugging; CB_DEBUG=1: a trace)");
  app.add_option("--parts", parts, "split the courses into this many parts (course k is in part k mod parts) ...")->check(CLI::Range(1, 1000));
  app.add_option("--part", part, "... and drive only this one (runs side by side; per_course merges)")->check(CLI::Range(0, 999));
  app.add_option("--world-out", world_dir, "write each driven course's world here (course_K.yaml)");
  app.add_option("--vision-latency", latency, "capture -> grid at collision avoidance [s]");
  app.add_option("--time-limit", time_limit, "per course and mode [s simulated]");
  CLI11_PARSE(app, argc, argv);
  cv::setNumThreads(1);   // one core, as the process runs

  nlohmann::json j;
  try {
    const bench::DriveConfig drive = bench::load_drive_config(config_dir);
    const auto& robot = drive.robot;
    const lld::LldOptions& lo = drive.lld;
    const auto& co = drive.ca;
    const std::string vision_path = config_dir + "/vision.yaml";
    const auto vcfg = config::Config::load(vision_path);
    vision::VisionNodeOptions vo = vision::load_vision_options(vcfg, robot, vision_path);
    vo.vision.rectangles.enabled = false;
    const auto scfg = config::Config::load(config_dir + "/stereo_capture_sim.yaml");
    const auto capture = stereo::load_capture_options(scfg.section("capture"), scfg.section("channels"),
                                                      runtime::default_data_dir(), config_dir);
    if (capture.calibration_id != vo.calibration_id)
      throw std::runtime_error("stereo_capture_sim.yaml sends calibration '" + capture.calibration_id + "', vision.yaml takes '" +
                               vo.calibration_id + "'");
    const auto calibration = stereo::load_stereo_calibration(vo.calibration_file);

    bench::FurnishedCourseOptions fo;
    fo.clearance = co.ca.planner.robot_radius + co.ca.planner.safety_margin;
    bench::HeadLoopOptions ho;
    ho.rate_hz = capture.rate_hz;
    ho.pan = capture.pan;
    ho.tilt = capture.tilt;
    ho.encoding = capture.encoding;
    ho.jpeg_quality = capture.jpeg_quality;
    ho.render.noise_sigma = capture.sim.noise_sigma;
    ho.latency_s = latency;
    ho.grid_occupied_min = co.ca.map.grid_occupied_min;

    std::mt19937 rng(static_cast<uint32_t>(seed));
    ModeTotals off, on;
    nlohmann::json per_course = nlohmann::json::array();
    std::vector<double> frame_ms;
    int redrawn = 0, tables = 0, chairs = 0, shelves = 0, driven = 0;
    for (int k = 0; k < ncourses; ++k) {
      const bench::FurnishedCourse fc = bench::draw_furnished_course(rng, fo);
      redrawn += fc.redrawn;
      if (only >= 0 && k != only) continue;
      if (k % parts != part) continue;
      ++driven;
      if (!world_dir.empty()) std::ofstream(world_dir + "/course_" + std::to_string(k) + ".yaml") << sim::world_to_yaml(fc.course.world);
      tables += fc.tables;
      chairs += fc.chairs;
      shelves += fc.shelves;
      bench::CourseDriveOptions o;
      o.sim = bench::control_sim_options(seed + 100 + static_cast<uint64_t>(k), true);
      o.sim.robot.radius = robot.radius;
      o.sim.robot.height = robot.height;
      o.time_limit_s = time_limit;
      o.trace = getenv("CB_DEBUG") != nullptr;
      const bench::CourseDriveResult r_off = bench::drive_course(fc.course, k, lo, co.ca, o);
      ho.render.noise_seed = seed + static_cast<uint64_t>(k);
      bench::HeadInTheLoop head(fc.course.world, calibration, vo, ho);
      o.after_step = [&head](const sim::Simulator& s, const sim::StepOutput& out, collision_avoidance::CollisionAvoidance& ca) {
        head.after_step(s, out, ca);
      };
      const bench::CourseDriveResult r_on = bench::drive_course(fc.course, k, lo, co.ca, o);
      nlohmann::json seen = nlohmann::json::array();
      for (const auto& c : head.contacts())
        seen.push_back({{"with", c.with}, {"t_s", c.t_s}, {"grid_age_s", c.grid_age_s}, {"cells_now", c.cells_now},
                        {"grids_marking", c.grids_marking}, {"last_marked_age_s", c.last_marked_age_s}});
      frame_ms.insert(frame_ms.end(), head.frame_ms().begin(), head.frame_ms().end());
      per_course.push_back({{"course", k},
                            {"tables", fc.tables},
                            {"chairs", fc.chairs},
                            {"shelves", fc.shelves},
                            {"vision_off", off.add(r_off)},
                            {"vision_on", on.add(r_on)},
                            {"vision_on_contacts_in_grid", seen},
                            {"frames", head.frames()}});
      std::cerr << "course " << k << " (" << fc.tables << " tables, " << fc.chairs << " chairs, " << fc.shelves
                << " shelves): off " << r_off.collisions << " collisions, " << (r_off.arrived ? "reached" : "not reached")
                << " in " << r_off.time_s << " s; on " << r_on.collisions << " collisions, "
                << (r_on.arrived ? "reached" : "not reached") << " in " << r_on.time_s << " s, " << head.frames() << " frames";
      if (!seen.empty()) std::cerr << "; the grid on what was hit: " << seen.dump();
      std::cerr << "\n";
    }
    j["courses"] = driven;
    j["collisions_vision_off"] = off.collisions;
    j["collisions_vision_on"] = on.collisions;
    j["courses_collided_vision_off"] = off.collided;
    j["courses_collided_vision_on"] = on.collided;
    j["reached_vision_off"] = off.reached;
    j["reached_vision_on"] = on.reached;
    j["mean_time_s_vision_off"] = off.reached ? off.time_sum / off.reached : -1.0;
    j["mean_time_s_vision_on"] = on.reached ? on.time_sum / on.reached : -1.0;
    j["with_what_vision_off"] = off.with;
    j["with_what_vision_on"] = on.with;
    j["furniture"] = {{"tables", tables}, {"chairs", chairs}, {"shelves", shelves}, {"impassable_redrawn", redrawn}};
    j["head"] = {{"rate_hz", ho.rate_hz}, {"tilt_rad", ho.tilt}, {"latency_s", ho.latency_s},
                 {"vision_frame_ms_p50", bench::percentile(frame_ms, 0.5)}, {"frames", frame_ms.size()}};
    j["robot"] = {{"radius_m", robot.radius}, {"height_m", robot.height}};
    j["seed"] = seed;
    j["time_limit_s"] = time_limit;
    j["per_course"] = per_course;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_vision_courses: " << e.what() << "\n";
    return 1;
  }
  const std::string text = j.dump(2) + "\n";
  if (out_path.empty()) std::cout << text;
  else std::ofstream(out_path) << text;
  return 0;
}
