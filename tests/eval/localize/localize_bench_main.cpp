// ./rgnav bench localize: rgnav's localizer on maps built by rgnav's own pipeline, driven by the
// simulator with the config's odometry error and walking people, against the simulator's truth:
// tracking along the world's tour, global localization from random starts, kidnaps. Every drive
// is also written for MRPT's pf-localization (deploy/bench/mrpt), which the bench script runs
// beside it. The keys are described in deploy/bench/localize.sh.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "carmen_drive.h"
#include "config/finish_except.h"
#include "localizer/localizer.h"
#include "offline_run.h"
#include "render/rgmap_picture.h"
#include "runtime/process_main.h"
#include "sim/sim_options.h"
#include "sim/tour_planner.h"
#include "sim/world_yaml.h"
#include "sim_drive.h"
#include "sim_rgmap.h"
#include "truth_frames.h"

namespace rp = rgnav::rgmap_pipeline;
namespace le = rgnav::localize_eval;
namespace lo = rgnav::localizer;
using rgnav::geometry::normalize_angle;
using rgnav::geometry::Pose2;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kGoodXy = 0.3, kGoodTheta = 10.0 * kDeg;   // "localized" (issue targets)
constexpr double kDivergedXy = 0.5;

double thread_cpu()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::pair<std::string, std::string> split_spec(const std::string& spec)
{
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) throw std::runtime_error("expected NAME=PATH, got '" + spec + "'");
  return {spec.substr(0, eq), spec.substr(eq + 1)};
}

double percentile(std::vector<double> v, double q)
{
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// Walkers for a world that has none: people pacing stretches of the robot's own tour (they
// meet it head on in hallways and doors, the hard case for scan matching).
void add_walkers(rgnav::sim::World* world, const std::vector<rgnav::sim::Vec2>& tour, int count)
{
  if (!world->people.empty() || tour.size() < 4) return;
  for (int i = 0; i < count; ++i) {
    rgnav::sim::Person p;
    p.name = "bench_walker_" + std::to_string(i);
    const size_t a = tour.size() * static_cast<size_t>(i + 1) / static_cast<size_t>(count + 1);
    for (size_t k = a; k < std::min(tour.size(), a + 6); ++k) p.path.push_back(tour[k]);
    std::reverse(p.path.begin(), p.path.end());
    p.loop = false;
    p.speed = 0.6 + 0.1 * i;
    world->people.push_back(p);
  }
}

// Error of an estimate against the truth, in the estimate's region frame.
struct Error
{
  double xy = 0, theta = 0;
  bool good() const { return xy <= kGoodXy && theta <= kGoodTheta; }
};
Error error_of(const lo::Estimate& e, const le::TruthFrames& frames, const Pose2& truth)
{
  const Pose2 t = frames.in_region(e.region, truth);
  return {(e.region_from_base.translation() - t.translation()).norm(), std::fabs(normalize_angle(e.region_from_base.theta() - t.theta()))};
}

// "Localized and staying so": the time after which every update is good to the end.
struct Settling
{
  double last_bad_s = 0;     // time of the newest bad (or missing) estimate
  double first_good_after = NAN, distance_at = NAN;
  bool good_now = false;
  void add(double t, double distance, bool good)
  {
    if (!good) {
      last_bad_s = t;
      good_now = false;
      first_good_after = NAN;
    } else if (!good_now) {
      good_now = true;
      first_good_after = t;
      distance_at = distance;
    }
  }
};

struct WorldSetup
{
  rgnav::sim::World world;
  std::vector<rgnav::sim::Vec2> tour;
  rgnav::rgmap::RgMap map;
  le::TruthFrames frames;
  std::map<int64_t, Pose2> grid_from_region;
  std::string dir;
};

Pose2 truth_in_grid(const WorldSetup& w, int64_t region, const Pose2& truth)
{
  return w.grid_from_region.at(region) * w.frames.in_region(region, truth);
}

// A random point along the tour, with the heading toward the next waypoint.
std::pair<size_t, double> random_tour_point(const std::vector<rgnav::sim::Vec2>& tour, std::mt19937_64& rng)
{
  std::vector<double> lengths;
  for (size_t k = 0; k + 1 < tour.size(); ++k) lengths.push_back((tour[k + 1] - tour[k]).norm());
  std::discrete_distribution<size_t> pick(lengths.begin(), lengths.end());
  return {pick(rng), std::uniform_real_distribution<double>(0.0, 1.0)(rng)};
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Localization benchmark: rgnav's localizer on its own maps of simulated worlds"};
  const std::string cfg_dir = rgnav::runtime::default_config_dir();
  rp::PipelineConfigPaths paths{cfg_dir + "/scan_mapper.yaml", cfg_dir + "/gateway_detector_aligned.yaml", cfg_dir + "/rg_kernel.yaml",
                                cfg_dir + "/robot.yaml"};
  std::string sim_config = cfg_dir + "/sim.yaml", localizer_config = cfg_dir + "/localizer.yaml", json_path, out_dir;
  std::vector<std::string> sims;
  int laps = 2, global_trials = 50, kidnaps = 10, walkers = 3, mrpt_global = 10, mrpt_scan_every = 3;
  uint64_t seed = 7;
  app.add_option("--localizer-config", localizer_config, "localizer config")->check(CLI::ExistingFile);
  app.add_option("--config", paths.scan_mapper, "scan mapper config (mapping)")->check(CLI::ExistingFile);
  app.add_option("--gateway-config", paths.gateway_detector, "gateway detector config (mapping)")->check(CLI::ExistingFile);
  app.add_option("--rg-config", paths.rg_kernel, "RG kernel config (mapping)")->check(CLI::ExistingFile);
  app.add_option("--robot", paths.robot, "robot description")->check(CLI::ExistingFile);
  app.add_option("--sim-config", sim_config, "simulator config (odometry error, laser)")->check(CLI::ExistingFile);
  app.add_option("--sim", sims, "NAME=WORLD (world file or IPA map image), repeatable")->required();
  app.add_option("--laps", laps, "tour laps of the tracking drive")->check(CLI::Range(1, 20));
  app.add_option("--global-trials", global_trials, "random starts per world")->check(CLI::Range(0, 10000));
  app.add_option("--kidnaps", kidnaps, "kidnaps per world")->check(CLI::Range(0, 10000));
  app.add_option("--walkers", walkers, "people added to a world that has none")->check(CLI::Range(0, 20));
  app.add_option("--mrpt-global", mrpt_global, "global trials per world also written for MRPT")->check(CLI::Range(0, 10000));
  app.add_option("--mrpt-scan-every", mrpt_scan_every, "every n-th scan written for MRPT")->check(CLI::Range(1, 100));
  app.add_option("--seed", seed, "random starts and simulator seeds");
  app.add_option("--json", json_path, "output JSON")->required();
  app.add_option("--out", out_dir, "folder for maps and drives")->required();
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::warn);
  try {
    const rp::LoadedPipeline loaded = rp::load_pipeline(paths);
    const auto sim_cfg = rgnav::config::Config::load(sim_config);
    const auto sim_options = rgnav::sim::load_simulator_options(sim_cfg, loaded.robot);
    rgnav::config::finish_except(sim_cfg, {"node", "channels", "sim", "protocol"});
    const auto loc_cfg = rgnav::config::Config::load(localizer_config);
    const auto loc_options = lo::load_localizer_options(loc_cfg, loaded.robot).localizer;
    rgnav::config::finish_except(loc_cfg, {"node"});
    const Pose2 base_from_laser = loc_options.base_from_laser;

    std::mt19937_64 rng(seed);
    nlohmann::json j;
    j["localizer_config"] = localizer_config;
    j["laps"] = laps;
    std::vector<double> track_xy, track_th, global_time, global_travel, flag_time, recover_time, update_cpu;
    int64_t handovers = 0, divergences = 0, false_kidnaps = 0, global_ok = 0, global_n = 0, kidnap_ok = 0, kidnap_n = 0;
    int64_t global_estimate_ok = 0, global_wrong = 0;
    int64_t gateway_events = 0, particles_sum = 0, updates_total = 0;
    double cpu_total = 0, sim_total = 0, max_bytes = 0;

    for (const auto& spec : sims) {
      const auto [name, path] = split_spec(spec);
      WorldSetup w;
      w.dir = out_dir + "/" + name;
      w.world = rgnav::sim::load_world(path);
      const auto tour = rgnav::sim::plan_tour(w.world, sim_options.robot);
      w.tour = tour.waypoints;
      // The map: one lap of the tour, mapped by scan mapper + gateway detector + RG kernel.
      rp::SimTourOptions mapping;
      mapping.laps = 1;
      mapping.max_sim_s = 2400;
      const auto run = rp::run_sim_rgmap(w.world, sim_options, loaded, mapping);
      rp::write_run_outputs(run.run, loaded.options, w.dir);
      w.map = run.run.map;
      w.frames = le::fit_truth_frames(run.run, run.truth_at_node, base_from_laser);
      w.frames.map = &w.map;
      w.grid_from_region = rgnav::render::compose_region_frames(w.map);
      // A fresh folder: MRPT's runner takes every drive folder it finds there.
      std::filesystem::remove_all(w.dir + "/mrpt");
      std::filesystem::create_directories(w.dir + "/mrpt");
      rgnav::render::write_map_server(rgnav::render::compose_global_grid(w.map, 0.05), w.dir + "/mrpt/map");
      add_walkers(&w.world, w.tour, walkers);
      nlohmann::json wj;
      wj["world"] = path;
      wj["regions"] = static_cast<int>(w.frames.world_from_region.size());
      {
        std::vector<double> fit;
        for (const auto& [id, e] : w.frames.fit_rmse) fit.push_back(e);
        wj["region_fit_rmse_m_p50"] = number_or_null(percentile(fit, 0.5));
        wj["region_fit_rmse_m_max"] = number_or_null(fit.empty() ? NAN : *std::max_element(fit.begin(), fit.end()));
      }

      lo::Localizer loc(loc_options);
      {
        const auto t0 = std::chrono::steady_clock::now();
        loc.set_map(w.map);
        wj["map_load_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      }
      // How far a gateway's transform between its two regions is from their true placement, at
      // the gateway: the map's own inconsistency, which no localizer can undo at a hand-over.
      {
        std::vector<double> link_errors;
        for (const auto& [id, g] : w.map.gateways()) {
          const int64_t a = w.map.resolve(g.region_a), b = g.region_b ? w.map.resolve(g.region_b) : 0;
          if (b == 0 || a == b || g.neutralized || !w.frames.world_from_region.count(a) || !w.frames.world_from_region.count(b) ||
              g.crossing_points.empty())
            continue;
          const Pose2 truth_ab = w.frames.world_from_region.at(a).inverse() * w.frames.world_from_region.at(b);
          const Eigen::Vector2d at_a = g.crossing_points.front();
          const Eigen::Vector2d via_link = g.region_a_from_region_b * (truth_ab.inverse() * at_a);
          link_errors.push_back((via_link - at_a).norm());
          if (std::getenv("LOCALIZE_TRACE"))
            std::cerr << name << " gateway " << id << " regions " << a << "-" << b << " link error " << link_errors.back() << " m\n";
        }
        wj["gateway_link_error_m_p50"] = number_or_null(percentile(link_errors, 0.5));
        wj["gateway_link_error_m_max"] = number_or_null(link_errors.empty() ? NAN : *std::max_element(link_errors.begin(), link_errors.end()));
      }
      max_bytes = std::max(max_bytes, static_cast<double>(loc.maps().bytes()));
      int64_t utime = sim_options.start_utime;
      const auto new_drive = [&](const std::vector<rgnav::sim::Vec2>& route, double max_s, const Pose2& odom_offset) {
        le::DriveSpec d;
        d.route = route;
        d.start_heading = route.size() > 1 ? std::atan2(route[1].y() - route[0].y(), route[1].x() - route[0].x()) : 0.0;
        d.max_s = max_s;
        d.start_utime = utime;
        d.odom_offset = odom_offset;
        d.seed = rng();
        return d;
      };

      // Tracking: the tour, `laps` times, from the pose the robot is put down at.
      {
        std::vector<rgnav::sim::Vec2> route;
        for (int lap = 0; lap < laps; ++lap) route.insert(route.end(), w.tour.begin() + (lap == 0 ? 0 : 1), w.tour.end());
        auto d = new_drive(route, 3600.0 * laps, Pose2());
        le::CarmenDrive mrpt(w.dir + "/mrpt/track", base_from_laser, mrpt_scan_every);
        const Pose2 start(route[0], d.start_heading);
        const int64_t r0 = w.frames.region_at(start);
        if (r0 == 0) throw std::runtime_error(name + ": the start lies in no region of the map");
        loc.set_pose(r0, w.frames.in_region(r0, start), loc_options.initial_xy, loc_options.initial_theta_deg * kDeg);
        mrpt.start("tracking", truth_in_grid(w, r0, start));
        const auto h0 = loc.stats().handovers;
        std::vector<double> exy, eth;
        std::ofstream trace;
        if (std::getenv("LOCALIZE_TRACE")) trace.open(w.dir + "/tracking_trace.txt");
        bool diverged = false;
        int64_t div = 0, updates = 0, particles = 0, events = 0;
        double cpu = 0;
        const auto res = le::run_drive(
            w.world, sim_options, d,
            [&](const le::DriveStep& s) {
              const double c0 = thread_cpu();
              const bool updated = loc.update(s.scan, s.odom_from_base);
              cpu += thread_cpu() - c0;
              if (loc.take_kidnap_flag()) ++false_kidnaps;
              events += static_cast<int64_t>(loc.take_gateway_events().size());
              const int64_t rt = w.frames.region_at(s.world_from_base, loc.estimate().region);
              const Pose2 tg = rt ? truth_in_grid(w, rt, s.world_from_base) : Pose2();
              mrpt.scan(s.scan, s.odom_from_base, rt ? &tg : nullptr);
              if (!updated || !loc.estimate().valid) return;
              ++updates;
              particles += loc.stats().particles;
              const Error e = error_of(loc.estimate(), w.frames, s.world_from_base);
              if (trace) {
                const auto& est = loc.estimate();
                const Pose2 t = w.frames.in_region(est.region, s.world_from_base);
                trace << s.time_s << " r" << est.region << " truth_r" << rt << " est " << est.region_from_base.x() << " "
                      << est.region_from_base.y() << " " << est.region_from_base.theta() << " true " << t.x() << " " << t.y() << " "
                      << t.theta() << " err " << e.xy << " share " << est.cluster_share << " in " << est.inlier_ratio << " n "
                      << loc.stats().particles << "\n";
                if (est.inlier_ratio < 0.2) {
                  const auto* m = loc.maps().region(est.region);
                  const auto pts = lo::beam_end_points(s.scan, base_from_laser, 60);
                  trace << "  debug: field empty " << m->field.empty() << " points " << pts.size() << " world " << s.world_from_base.x() << " "
                        << s.world_from_base.y() << " dists";
                  for (size_t k = 0; k < pts.size(); k += 6) trace << " " << m->field.distance(est.region_from_base * pts[k]);
                  trace << "\n";
                }
              }
              exy.push_back(e.xy);
              eth.push_back(e.theta / kDeg);
              if (e.xy > kDivergedXy && !diverged) ++div;
              diverged = e.xy > kDivergedXy;
            },
            [&](const le::OdometryStep& o) { mrpt.odometry(o.utime, o.odom_from_base, o.v, o.omega); });
        utime = res.end_utime + 1'000'000;
        double se = 0, st = 0;
        for (size_t k = 0; k < exy.size(); ++k) {
          se += exy[k] * exy[k];
          st += eth[k] * eth[k];
        }
        const double n = std::max<double>(1, static_cast<double>(exy.size()));
        nlohmann::json t;
        t["seconds"] = res.seconds;
        t["distance_m"] = res.distance;
        t["updates"] = updates;
        t["rmse_m"] = std::sqrt(se / n);
        t["rmse_deg"] = std::sqrt(st / n);
        t["p95_m"] = number_or_null(percentile(exy, 0.95));
        t["p95_deg"] = number_or_null(percentile(eth, 0.95));
        t["max_m"] = exy.empty() ? 0.0 : *std::max_element(exy.begin(), exy.end());
        t["max_deg"] = eth.empty() ? 0.0 : *std::max_element(eth.begin(), eth.end());
        t["handovers"] = loc.stats().handovers - h0;
        t["gateway_passed_events"] = events;
        t["divergences"] = div;
        t["cpu_s"] = cpu;
        t["cpu_ms_per_update"] = updates ? 1e3 * cpu / static_cast<double>(updates) : 0.0;
        t["cpu_core_share"] = cpu / std::max(1e-9, res.seconds);
        t["particles_mean"] = updates ? static_cast<double>(particles) / static_cast<double>(updates) : 0.0;
        wj["tracking"] = t;
        track_xy.insert(track_xy.end(), exy.begin(), exy.end());
        track_th.insert(track_th.end(), eth.begin(), eth.end());
        handovers += loc.stats().handovers - h0;
        divergences += div;
        gateway_events += events;
        cpu_total += cpu;
        sim_total += res.seconds;
        particles_sum += particles;
        updates_total += updates;
        if (updates) update_cpu.push_back(1e3 * cpu / static_cast<double>(updates));
      }

      // Global localization from random starts: 30 s drives along the tour from a random point.
      {
        int ok = 0, estimate_ok = 0, wrong_claims = 0;
        std::vector<double> times, travels;
        for (int trial = 0; trial < global_trials; ++trial) {
          const auto [k, s] = random_tour_point(w.tour, rng);
          const auto route = le::route_from(w.tour, k, s, 40.0);
          auto d = new_drive(route, 30.0, Pose2());
          loc.start_global();
          std::unique_ptr<le::CarmenDrive> mrpt;
          if (trial < mrpt_global) mrpt = std::make_unique<le::CarmenDrive>(w.dir + "/mrpt/global_" + std::to_string(trial), base_from_laser, mrpt_scan_every);
          Settling settle, settle_estimate;
          Error last_error;
          bool started = false, wrong_claim = false;
          const auto res = le::run_drive(
              w.world, sim_options, d,
              [&](const le::DriveStep& st) {
                const int64_t rt = w.frames.region_at(st.world_from_base, loc.estimate().region);
                if (mrpt) {
                  const Pose2 tg = rt ? truth_in_grid(w, rt, st.world_from_base) : Pose2();
                  if (!started && rt) mrpt->start("global", tg);
                  started = started || rt;
                  mrpt->scan(st.scan, st.odom_from_base, rt ? &tg : nullptr);
                }
                if (!loc.update(st.scan, st.odom_from_base)) return;
                const Error e = error_of(loc.estimate(), w.frames, st.world_from_base);
                const bool claimed = loc.estimate().valid && loc.mode() == lo::Mode::kTracking;
                settle.add(st.time_s, st.true_distance, claimed && e.good());
                settle_estimate.add(st.time_s, st.true_distance, loc.estimate().valid && e.good());
                wrong_claim = wrong_claim || (claimed && e.xy > kDivergedXy);
                last_error = e;
              },
              [&](const le::OdometryStep& o) {
                if (mrpt) mrpt->odometry(o.utime, o.odom_from_base, o.v, o.omega);
              });
          utime = res.end_utime + 1'000'000;
          const bool success = settle.good_now && settle.first_good_after <= 10.0;
          ok += success;
          estimate_ok += settle_estimate.good_now && settle_estimate.first_good_after <= 10.0;
          wrong_claims += wrong_claim;
          if (std::getenv("LOCALIZE_TRACE"))
            std::cerr << name << " global " << trial << (success ? " ok" : " FAIL") << " settled " << settle.first_good_after
                      << " error " << last_error.xy << " m " << last_error.theta / kDeg << " deg mode " << lo::to_string(loc.mode())
                      << " share " << loc.estimate().cluster_share << " inliers " << loc.estimate().inlier_ratio << " region "
                      << loc.estimate().region << " fit " << w.frames.fit_rmse[loc.estimate().region] << " start " << route[0].x()
                      << " " << route[0].y() << "\n";
          if (settle.good_now) {
            times.push_back(settle.first_good_after);
            travels.push_back(settle.distance_at);
          }
        }
        nlohmann::json g;
        g["trials"] = global_trials;
        g["success_ratio"] = global_trials ? static_cast<double>(ok) / global_trials : 0.0;
        g["estimate_success_ratio"] = global_trials ? static_cast<double>(estimate_ok) / global_trials : 0.0;
        g["wrong_claims"] = wrong_claims;
        g["time_s_p50"] = number_or_null(percentile(times, 0.5));
        g["travel_m_p50"] = number_or_null(percentile(travels, 0.5));
        wj["global"] = g;
        global_ok += ok;
        global_estimate_ok += estimate_ok;
        global_wrong += wrong_claims;
        global_n += global_trials;
        global_time.insert(global_time.end(), times.begin(), times.end());
        global_travel.insert(global_travel.end(), travels.begin(), travels.end());
      }

      // Kidnaps: 10 s of tracking, then the robot is carried to another random place (its
      // odometry goes on where it was) and driven on for 40 s.
      {
        int ok = 0, flagged = 0;
        std::vector<double> flags, recovers;
        for (int trial = 0; trial < kidnaps; ++trial) {
          const auto [k, s] = random_tour_point(w.tour, rng);
          const auto route = le::route_from(w.tour, k, s, 20.0);
          auto d = new_drive(route, 10.0, Pose2());
          const Pose2 start(route[0], d.start_heading);
          const int64_t r0 = w.frames.region_at(start);
          if (r0 == 0 || !loc.set_pose(r0, w.frames.in_region(r0, start), loc_options.initial_xy, loc_options.initial_theta_deg * kDeg)) {
            --trial;
            continue;
          }
          const auto a = le::run_drive(w.world, sim_options, d, [&](const le::DriveStep& st) { loc.update(st.scan, st.odom_from_base); });
          loc.take_kidnap_flag();
          // Somewhere at least 5 m away.
          std::vector<rgnav::sim::Vec2> route_b;
          for (int attempt = 0; attempt < 50; ++attempt) {
            const auto [kb, sb] = random_tour_point(w.tour, rng);
            route_b = le::route_from(w.tour, kb, sb, 40.0);
            if ((route_b[0] - route.back()).norm() >= 5.0) break;
          }
          utime = a.end_utime + 100'000;
          auto db = new_drive(route_b, 40.0, a.end_odom);
          Settling settle;
          double flag_s = NAN;
          const auto b = le::run_drive(w.world, sim_options, db, [&](const le::DriveStep& st) {
            const bool updated = loc.update(st.scan, st.odom_from_base);
            if (loc.take_kidnap_flag() && std::isnan(flag_s)) flag_s = st.time_s;
            if (!updated) return;
            const bool good = loc.estimate().valid && loc.mode() == lo::Mode::kTracking &&
                              error_of(loc.estimate(), w.frames, st.world_from_base).good();
            settle.add(st.time_s, st.true_distance, good);
          });
          utime = b.end_utime + 1'000'000;
          if (!std::isnan(flag_s)) {
            ++flagged;
            flags.push_back(flag_s);
          }
          const bool recovered = settle.good_now && settle.first_good_after <= 30.0;
          ok += recovered;
          if (settle.good_now) recovers.push_back(settle.first_good_after);
        }
        nlohmann::json kj;
        kj["trials"] = kidnaps;
        kj["flagged"] = flagged;
        kj["flag_s_p50"] = number_or_null(percentile(flags, 0.5));
        kj["recovered_ratio"] = kidnaps ? static_cast<double>(ok) / kidnaps : 0.0;
        kj["recover_s_p50"] = number_or_null(percentile(recovers, 0.5));
        wj["kidnap"] = kj;
        kidnap_ok += ok;
        kidnap_n += kidnaps;
        flag_time.insert(flag_time.end(), flags.begin(), flags.end());
        recover_time.insert(recover_time.end(), recovers.begin(), recovers.end());
      }
      j["worlds"][name] = wj;
      std::cerr << "localize bench: " << name << " " << wj.dump() << "\n";
    }

    double se = 0, st = 0;
    for (size_t k = 0; k < track_xy.size(); ++k) {
      se += track_xy[k] * track_xy[k];
      st += track_th[k] * track_th[k];
    }
    const double n = std::max<double>(1, static_cast<double>(track_xy.size()));
    j["tracking_updates"] = static_cast<int64_t>(track_xy.size());
    j["tracking_rmse_m"] = std::sqrt(se / n);
    j["tracking_rmse_deg"] = std::sqrt(st / n);
    j["tracking_p95_m"] = number_or_null(percentile(track_xy, 0.95));
    j["tracking_max_m"] = track_xy.empty() ? 0.0 : *std::max_element(track_xy.begin(), track_xy.end());
    j["tracking_max_deg"] = track_th.empty() ? 0.0 : *std::max_element(track_th.begin(), track_th.end());
    j["handovers"] = handovers;
    j["gateway_passed_events"] = gateway_events;
    j["divergences"] = divergences;
    j["false_kidnaps"] = false_kidnaps;
    j["global_trials"] = global_n;
    j["global_success_ratio"] = global_n ? static_cast<double>(global_ok) / static_cast<double>(global_n) : 0.0;
    j["global_time_s_p50"] = number_or_null(percentile(global_time, 0.5));
    // The estimate right (and staying so) within 10 s whether or not the localizer claims it yet,
    // and the trials in which it claimed a pose that was > 0.5 m wrong.
    j["global_estimate_success_ratio"] = global_n ? static_cast<double>(global_estimate_ok) / static_cast<double>(global_n) : 0.0;
    j["global_wrong_claims"] = global_wrong;
    j["global_travel_m_p50"] = number_or_null(percentile(global_travel, 0.5));
    j["kidnap_trials"] = kidnap_n;
    j["kidnap_flag_s_p50"] = number_or_null(percentile(flag_time, 0.5));
    j["kidnap_flagged_ratio"] = kidnap_n ? static_cast<double>(flag_time.size()) / static_cast<double>(kidnap_n) : 0.0;
    j["kidnap_recovered_ratio"] = kidnap_n ? static_cast<double>(kidnap_ok) / static_cast<double>(kidnap_n) : 0.0;
    j["kidnap_recover_s_p50"] = number_or_null(percentile(recover_time, 0.5));
    j["cpu_core_share"] = cpu_total / std::max(1e-9, sim_total);
    j["cpu_ms_per_update_p50"] = number_or_null(percentile(update_cpu, 0.5));
    j["particles_mean"] = updates_total ? static_cast<double>(particles_sum) / static_cast<double>(updates_total) : 0.0;
    j["map_memory_mb_max"] = max_bytes / 1e6;
    std::filesystem::create_directories(std::filesystem::path(json_path).parent_path());
    std::ofstream(json_path) << j.dump(2) << "\n";
    std::cout << j.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "localize bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
