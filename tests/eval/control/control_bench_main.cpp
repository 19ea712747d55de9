// control_bench: closes the loop lld + collision avoidance around the simulated B21r
// (drivers/sim, lock-step, odometry noise, ray-cast LMS 2xx, walking people) and measures
//   - tracking: cross-track error of the odometry pose the lld tracks (and of the true pose)
//     over mixed chains (lines, arcs, clothoids) at 0.3 and 0.6 m/s; predicted vs actual time;
//   - obstacle courses: randomised corridors with boxes and people; collisions, targets
//     reached, time. People keep a personal space from the robot walking toward it
//     (--personal-space, default 0.4 m; --oblivious-too repeats the courses with people who
//     only avoid touching it). Targets follow the odometry drift as a localizer would.
//   - tours (--tours N): the office world's whole tour driven as the demo drives it
//     (office_tour.h); targets reached, time, the longest stall between two targets.
//   - doorway encounters (--doorways N): generated doorways and narrow hallways with a person
//     coming the other way who waits, stands aside or goes around at random
//     (doorway_encounters.h); resolved, collisions, deadlocks, time lost.
// Loop timing of the real lld executable is measured by deploy/bench/control.sh.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "lld/follower.h"
#include "lld/lld_options.h"
#include "sim/simulator.h"
#include "sim/world_yaml.h"
#include "trajectory/construct.h"

#include "course_drive.h"
#include "doorway_encounters.h"
#include "obstacle_course.h"
#include "office_tour.h"

using namespace rgnav;
using trajectory::Chain;
using trajectory::Segment;
using geometry::Pose2;

namespace {

constexpr double kPeriod = 0.05;
const auto kPeriodUs = std::chrono::microseconds(50'000);

Pose2 to_pose(const sim::Pose2& p) { return Pose2(p.x, p.y, p.theta); }

// A mixed G2 chain: lines, clothoid-arc-clothoid turns both ways, a clothoid S-bend.
Chain mixed_chain(std::mt19937& rng, double v)
{
  std::uniform_real_distribution<double> turn(0.6, 1.8), len(0.8, 2.0), kap(0.8, 2.0);
  Chain c;
  c.push_back(Segment::line(Pose2(), len(rng)));
  double sign = 1.0;
  for (int i = 0; i < 4; ++i) {
    const Chain t = trajectory::smooth_turn(c.end(), sign * turn(rng), kap(rng));
    for (const auto& s : t.segments()) c.append_at_end(s);
    c.append_at_end(Segment::line(Pose2(), len(rng)));
    sign = -sign;
  }
  // S-bend by a G1 clothoid to a parallel offset pose (curvature jumps at its ends).
  const Pose2 e = c.end();
  if (auto s = trajectory::clothoid_g1(e, e * Pose2(2.0, 0.4, 0.0))) c.append_at_end(*s);
  c.append_at_end(Segment::line(Pose2(), 1.0));
  std::vector<Segment> segs;
  for (auto s : c.segments()) {
    s.set_v_max(v);
    segs.push_back(s);
  }
  return Chain(segs);
}

struct Stats
{
  double sum2 = 0.0, max = 0.0;
  int64_t n = 0;
  void add(double x)
  {
    sum2 += x * x;
    max = std::max(max, std::fabs(x));
    ++n;
  }
  double rms() const { return n ? std::sqrt(sum2 / n) : 0.0; }
};

nlohmann::json tracking(const lld::LldOptions& lo, double v, int chains, uint64_t seed, double* time_err_max,
                        Stats* odo_all)
{
  std::mt19937 rng(static_cast<uint32_t>(seed));
  Stats odo, truth;
  double terr_sum = 0.0, terr_max = 0.0;
  int done = 0;
  for (int k = 0; k < chains; ++k) {
    sim::World world;
    world.name = "empty";
    sim::Simulator sim(world, bench::control_sim_options(seed + k, false));
    sim::TimedCommandSource cmd;
    sim.set_command_source(&cmd);
    lld::Follower f(lo.follower);
    trajectory::Trajectory t;
    t.id = 1;
    t.chain = mixed_chain(rng, v);
    t.a_max = 0.5;
    t.omega_max = 1.2;
    lld::OdometryInput odi;
    bool have = false;
    for (const auto& o : sim.step(kPeriodUs).odometry) {  // first odometry
      odi = {to_pose(o.odom_from_base), o.v, o.omega, time::from_utime(o.utime)};
      have = true;
    }
    auto now = time::from_utime(sim.now_utime());
    f.replace(lld::make_plan(t, lo.follower, 0.0), now);
    const double predicted = f.plan()->profile.total_time();
    const Chain& chain = f.plan()->trajectory.chain;
    double finished = -1.0;
    const double t_start = sim.time_s();
    double s_true = 0.0;
    for (int i = 0; i < 20000; ++i) {
      now = time::from_utime(sim.now_utime());
      const auto& st = f.step(now, kPeriod, have ? &odi : nullptr);
      f.refresh(1, now);
      cmd.set(sim.now_utime(), {st.command.v, st.command.omega}, lo.loop.command_deadline_ms * 1000);
      if (st.state == lld::FollowerState::kTracking && have && st.progress > 0.05 && st.progress < chain.length() - 0.05) {
        odo.add(st.cross_track);
        odo_all->add(st.cross_track);
        // True pose relative to the same chain (the odom frame starts at the true start pose).
        const auto pr = chain.project(to_pose(sim.truth()).translation(), std::max(0.0, s_true - 1.0), s_true + 1.0);
        s_true = pr.s;
        truth.add(pr.local.lateral);
      }
      if (st.state == lld::FollowerState::kDone) {
        finished = sim.time_s() - t_start;
        break;
      }
      const auto out = sim.step(kPeriodUs);
      if (!out.odometry.empty()) {
        const auto& o = out.odometry.back();
        odi = {to_pose(o.odom_from_base), o.v, o.omega, time::from_utime(o.utime)};
        have = true;
      }
    }
    if (finished > 0) {
      ++done;
      const double err = std::fabs(finished - predicted) / predicted * 100.0;
      terr_sum += err;
      terr_max = std::max(terr_max, err);
    }
  }
  *time_err_max = std::max(*time_err_max, terr_max);
  return {{"speed_mps", v},          {"chains", chains},          {"completed", done},
          {"xtrack_rms_m", odo.rms()}, {"xtrack_max_m", odo.max}, {"true_xtrack_rms_m", truth.rms()},
          {"true_xtrack_max_m", truth.max}, {"time_pred_err_mean_pct", done ? terr_sum / done : -1.0},
          {"time_pred_err_max_pct", terr_max}};
}

nlohmann::json courses(const lld::LldOptions& lo, const collision_avoidance::CaOptions& co, int n, uint64_t seed,
                       int only, double personal_space)
{
  std::mt19937 rng(static_cast<uint32_t>(seed));
  int64_t collisions = 0;
  int reached = 0;
  double time_sum = 0.0;
  int64_t fallbacks = 0, replans = 0;
  nlohmann::json failures = nlohmann::json::array();
  nlohmann::json contacts = nlohmann::json::array();
  std::map<std::string, int> closed_by;
  int redrawn = 0;
  const double clearance = co.planner.robot_radius + co.planner.safety_margin;
  for (int k = 0; k < n; ++k) {
    const bench::CourseDraw draw = bench::draw_course(rng, clearance, personal_space);
    redrawn += draw.redrawn;
    const bench::Course& course = draw.course;
    if (only >= 0 && k != only) continue;  // debugging one course: the others are drawn, not run
    if (getenv("CB_DEBUG")) {
      for (const auto& b : course.world.boxes)
        std::cerr << "box " << b.center.x() << "," << b.center.y() << " size " << b.size.x() << "x" << b.size.y() << " yaw " << b.yaw << "\n";
      for (const auto& p : course.world.people)
        std::cerr << "person from " << p.path[0].x() << "," << p.path[0].y() << " speed " << p.speed << " delay " << p.start_delay << "\n";
    }
    bench::CourseDriveOptions o;
    o.sim = bench::control_sim_options(seed + 100 + k, true);
    o.trace = getenv("CB_DEBUG") != nullptr;
    o.trace_nearest = getenv("CB_DEBUG_NEAREST") != nullptr;
    const bench::CourseDriveResult r = bench::drive_course(course, k, lo, co, o);
    for (const auto& c : r.contacts) {
      contacts.push_back(c);
      closed_by[c.value("closed_by", std::string("obstacle"))]++;
    }
    collisions += r.collisions;
    fallbacks += r.fallbacks;
    replans += r.replans;
    if (r.arrived) {
      ++reached;
      time_sum += r.time_s;
    } else {
      failures.push_back({{"course", k}, {"x", r.end.x}, {"y", r.end.y}, {"mode", r.mode}});
    }
  }
  return {{"courses", n},
          {"collisions", collisions},
          {"reached", reached},
          {"reached_ratio", n ? static_cast<double>(reached) / n : 0.0},
          {"mean_time_s", reached ? time_sum / reached : -1.0},
          {"course_length_m", 12.0},
          {"impassable_redrawn", redrawn},
          {"replans", replans},
          {"fallbacks", fallbacks},
          {"failures", failures},
          {"contacts_closed_by", closed_by},
          {"contacts", contacts}};
}

// The world's tour, driven `n` times with the people starting 0, 7, 14, ... s later (so
// that they meet the robot at other doors), each run with its own noise seed.
nlohmann::json tours(const lld::LldOptions& lo, const collision_avoidance::CaOptions& co, const std::string& world_path,
                     int n, uint64_t seed, int only)
{
  const sim::World world = sim::load_world(world_path);
  const std::vector<Eigen::Vector2d> waypoints = bench::demo_tour(world);
  if (waypoints.empty()) throw std::runtime_error(world_path + ": no tour through this world");
  nlohmann::json runs = nlohmann::json::array();
  int completed = 0;
  double time_sum = 0.0, worst_stall = 0.0;
  size_t reached = 0, targets = 0;
  int64_t collisions = 0;
  for (int k = 0; k < n; ++k) {
    if (only >= 0 && k != only) continue;
    bench::TourRunOptions o;
    o.seed = seed + 1000 + static_cast<uint64_t>(k);
    o.people_delay_s = 7.0 * k;
    o.trace = getenv("CB_DEBUG") != nullptr;
    const bench::TourRunResult r = bench::run_tour(world, waypoints, lo, co, o);
    std::cerr << "tour " << k << ": " << r.reached << "/" << r.targets << " in " << r.time_s << " s, longest stall "
              << r.longest_stall_s << " s at " << r.stall_at.x() << "," << r.stall_at.y() << "\n";
    runs.push_back({{"run", k},
                    {"people_delay_s", o.people_delay_s},
                    {"reached", r.reached},
                    {"targets", r.targets},
                    {"completed", r.completed()},
                    {"time_s", r.time_s},
                    {"longest_stall_s", r.longest_stall_s},
                    {"stall_at", {r.stall_at.x(), r.stall_at.y()}},
                    {"stall_target", r.stall_target},
                    {"collisions", r.collisions},
                    {"fallbacks", r.fallbacks}});
    completed += r.completed() ? 1 : 0;
    if (r.completed()) time_sum += r.time_s;
    worst_stall = std::max(worst_stall, r.longest_stall_s);
    reached += r.reached;
    targets += r.targets;
    collisions += r.collisions;
  }
  return {{"world", world_path},
          {"runs", runs},
          {"completed", completed},
          {"targets_reached_ratio", targets ? static_cast<double>(reached) / targets : 0.0},
          {"mean_time_s", completed ? time_sum / completed : -1.0},
          {"worst_stall_s", worst_stall},
          {"collisions", collisions}};
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app("control_bench");
  std::string config_dir = "config", out_path;
  int chains = 6, ncourses = 50, only = -1, ntours = 0, ndoorways = 60, doorway_only = -1;
  std::string tour_world = "config/worlds/office.yaml";
  double personal_space = 0.4;
  bool oblivious_too = false;
  uint64_t seed = 1;
  app.add_option("--config-dir", config_dir);
  app.add_option("--out", out_path)->required();
  app.add_option("--chains", chains);
  app.add_option("--courses", ncourses);
  app.add_option("--only", only,
                 "run only this course (debugging; CB_DEBUG=1: a trace, CB_DEBUG_NEAREST=1: the nearest obstacles)");
  app.add_option("--seed", seed);
  app.add_option("--doorways", ndoorways, "doorway and narrow-hallway encounters (0: none)");
  app.add_option("--doorway-only", doorway_only,
                 "run only this doorway encounter, and nothing else (debugging; CB_DEBUG=1: a trace)");
  app.add_option("--tours", ntours, "drive the tour world's tour this many times (people shifted 7 s each time)");
  app.add_option("--tour-world", tour_world, "world file; its tour, or the one the demo plans (default config/worlds/office.yaml)");
  app.add_option("--personal-space", personal_space,
                 "people walking toward the robot wait this far from it [m] (0: only rather than touch it)");
  app.add_flag("--oblivious-too", oblivious_too, "also run the courses with people who wait only rather than touch the robot");
  CLI11_PARSE(app, argc, argv);

  const bench::DriveConfig drive = bench::load_drive_config(config_dir);
  const lld::LldOptions& lo = drive.lld;
  const auto& co = drive.ca;

  nlohmann::json j;
  j["plant"] = "sim";
  if (doorway_only >= 0) {
    j["doorway_encounters"] = bench::doorway_encounters(lo, co.ca, std::max(ndoorways, doorway_only + 1), seed, doorway_only);
    std::ofstream(out_path) << j.dump(2) << "\n";
    std::cout << j["doorway_encounters"].dump(2) << "\n";
    return 0;
  }
  double terr_max = 0.0;
  Stats all_06;
  Stats dummy;
  j["tracking"] = nlohmann::json::array();
  j["tracking"].push_back(tracking(lo, 0.3, chains, seed, &terr_max, &dummy));
  j["tracking"].push_back(tracking(lo, 0.6, chains, seed + 50, &terr_max, &all_06));
  j["xtrack_rms_m"] = all_06.rms();
  j["xtrack_max_m"] = all_06.max;
  j["time_pred_err_pct"] = terr_max;
  auto cj = courses(lo, co.ca, ncourses, seed, only, personal_space);
  cj["personal_space_m"] = personal_space;
  j["obstacle_courses"] = cj;
  if (oblivious_too && personal_space > 0.0) {
    auto oj = courses(lo, co.ca, ncourses, seed, only, 0.0);
    oj["personal_space_m"] = 0.0;
    j["obstacle_courses_oblivious_people"] = oj;
  }
  if (ntours > 0) j["tours"] = tours(lo, co.ca, tour_world, ntours, seed, only);
  if (ndoorways > 0) j["doorway_encounters"] = bench::doorway_encounters(lo, co.ca, ndoorways, seed, -1);
  j["courses"] = cj["courses"];
  j["collisions"] = cj["collisions"];
  j["reached_ratio"] = cj["reached_ratio"];
  std::ofstream(out_path) << j.dump(2) << "\n";
  std::cout << j.dump(2) << "\n";
  return 0;
}
