// ./rgnav bench explore: rgnav's explorer (procs/explorer) with its planner, and a frontier
// explorer as the baseline, exploring simulated buildings from a fixed and from random starts;
// the keys are described in deploy/bench/explore.sh.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <atomic>
#include <mutex>
#include <random>
#include <thread>

#include "bench_world.h"
#include "config/finish_except.h"
#include "drive_loop.h"
#include "explore_drivers.h"
#include "explore_run.h"
#include "explorer/explorer_options.h"
#include "name_path_spec.h"
#include "planner/planner_options.h"
#include "runtime/process_main.h"
#include "sim/sim_options.h"
#include "sim/tour_planner.h"
#include "sim/world_yaml.h"
#include "sim_rgmap.h"

namespace rp = rgnav::rgmap_pipeline;
namespace ee = rgnav::explore_eval;
using nlohmann::json;

namespace {

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Worst (min or max) of a key over runs of one method; null when none has it.
json worst(const json& runs, const std::string& method, const std::string& key, bool max)
{
  double best = NAN;
  for (const auto& r : runs) {
    if (r["method"] != method || !r.contains(key) || !r[key].is_number()) continue;
    const double v = r[key].get<double>();
    best = std::isnan(best) ? v : max ? std::max(best, v) : std::min(best, v);
  }
  return num(best);
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Exploration benchmark: rgnav's explorer and a frontier explorer in simulated buildings"};
  const std::string cfg_dir = rgnav::runtime::default_config_dir();
  rp::PipelineConfigPaths paths{cfg_dir + "/scan_mapper.yaml", cfg_dir + "/gateway_detector_aligned.yaml", cfg_dir + "/rg_kernel.yaml",
                                cfg_dir + "/robot.yaml"};
  std::string sim_config = cfg_dir + "/sim.yaml", planner_config = cfg_dir + "/planner.yaml", lld_config = cfg_dir + "/lld.yaml",
              ca_config = cfg_dir + "/collision_avoidance.yaml", explorer_config = cfg_dir + "/explorer.yaml", json_path, out_dir;
  std::vector<std::string> sims, methods{"rgnav", "frontier"};
  int starts = 1, walkers = 3;
  uint64_t seed = 11;
  double max_sim_s = 3600.0, map_period_s = 1.0;
  app.add_option("--planner-config", planner_config, "planner config")->check(CLI::ExistingFile);
  app.add_option("--explorer-config", explorer_config, "explorer config")->check(CLI::ExistingFile);
  app.add_option("--lld-config", lld_config, "lld config")->check(CLI::ExistingFile);
  app.add_option("--ca-config", ca_config, "collision avoidance config")->check(CLI::ExistingFile);
  app.add_option("--config", paths.scan_mapper, "scan mapper config")->check(CLI::ExistingFile);
  app.add_option("--gateway-config", paths.gateway_detector, "gateway detector config")->check(CLI::ExistingFile);
  app.add_option("--rg-config", paths.rg_kernel, "RG kernel config")->check(CLI::ExistingFile);
  app.add_option("--robot", paths.robot, "robot description")->check(CLI::ExistingFile);
  app.add_option("--sim-config", sim_config, "simulator config (odometry error, laser)")->check(CLI::ExistingFile);
  app.add_option("--sim", sims, "NAME=WORLD (world file or IPA map image), repeatable")->required();
  app.add_option("--starts", starts, "random starts per world besides the world's own")->check(CLI::Range(0, 100));
  app.add_option("--methods", methods, "rgnav and/or frontier")->check(CLI::IsMember({"rgnav", "frontier"}));
  app.add_option("--max-sim-s", max_sim_s, "cap on simulated seconds per run (a timeout)")->check(CLI::Range(10.0, 36000.0));
  app.add_option("--map-period", map_period_s, "[s] the RG map reaches the explorer and planner at most this often")
      ->check(CLI::Range(0.05, 10.0));
  double spin_s = 0.0, cap_factor = 6.0;
  int jobs = 2;
  app.add_option("--cap-factor", cap_factor, "a run is capped at this many times the tour's time at 0.5 m/s (at most --max-sim-s)")
      ->check(CLI::Range(1.0, 100.0));
  app.add_option("--jobs", jobs, "runs at once (threads)")->check(CLI::Range(1, 16));
  bool laser_only = false;
  app.add_flag("--laser-only", laser_only,
               "collision avoidance without the vision stand-in (solids the laser misses stay unseen)");
  app.add_option("--spin-at-start", spin_s, "[s] the robot turns on the spot this long (0.5 rad/s) before exploring")
      ->check(CLI::Range(0.0, 60.0));
  app.add_option("--walkers", walkers, "people added to a world that has none")->check(CLI::Range(0, 20));
  app.add_option("--seed", seed, "random starts and simulator seeds");
  app.add_option("--json", json_path, "output JSON")->required();
  app.add_option("--out", out_dir, "folder for the explored maps")->required();
  CLI11_PARSE(app, argc, argv);
  const bool trace = std::getenv("EXPLORE_TRACE") != nullptr;
  spdlog::set_level(spdlog::level::warn);
  try {
    const auto bench_t0 = std::chrono::steady_clock::now();
    const rp::LoadedPipeline loaded = rp::load_pipeline(paths);
    const rgnav::plan_eval::DriveChainOptions chain =
        rgnav::plan_eval::load_drive_chain({sim_config, planner_config, lld_config, ca_config}, loaded.robot);
    const auto& sim_options = chain.sim;
    const auto& planner_options = chain.planner;
    const auto exp_cfg = rgnav::config::Config::load(explorer_config);
    auto explorer_options = rgnav::explorer::load_explorer_options(exp_cfg, loaded.robot);
    // As the explorer node reads the planner's config; here --planner-config names it.
    explorer_options.grid = planner_options.grid;
    exp_cfg.section("view").string("planner_config", "");
    rgnav::config::finish_except(exp_cfg, {"node", "channels", "pose", "step", "persist"});
    ee::RunSetup setup{loaded, chain.lld, chain.ca, chain.sim};
    setup.max_sim_s = max_sim_s;
    setup.trace = trace;
    setup.spin_at_start_s = spin_s;
    setup.vision = !laser_only;
    const auto& l = sim_options.laser;
    const rgnav::geometry::Pose2 base_from_laser(l.mount_x, l.mount_y, l.mount_yaw);
    ee::FrontierOptions frontier;
    frontier.robot_radius = sim_options.robot.radius;

    std::mt19937_64 rng(seed);
    json j;
    j["worlds"] = json::object();
    json all_runs = json::array();
    // Per world: the ground truth, the tour and its map, the starts (in order, one thread).
    struct WorldJob
    {
      std::string name;
      json wj;
      std::unique_ptr<ee::WorldTruth> truth;
      std::vector<ee::StartTruth> starts;
      double tour_precision = NAN;
      double cap_s = 0;
    };
    std::vector<WorldJob> world_jobs;
    for (const auto& spec : sims) {
      const auto [name, path] = rp::split_spec(spec);
      const auto world_t0 = std::chrono::steady_clock::now();
      WorldJob job;
      job.name = name;
      json& wj = job.wj;
      wj["world"] = path;
      rgnav::sim::World world = rgnav::sim::load_world(path);
      // The ground-truth tour from the world's start, and the map it drives (as ./rgnav bench rgmap).
      const auto tour = rgnav::sim::plan_tour(world, sim_options.robot);
      rp::SimTourOptions tour_options;
      tour_options.max_sim_s = 2400;
      const auto tour_run = rp::run_sim_rgmap(world, sim_options, loaded, tour_options);
      const auto tour_truth = rp::ground_truth_of(world);
      const auto tour_score = rp::score_world(tour_run, tour_truth, setup.gateway_match_m);
      job.tour_precision = tour_score.segmentation.precision;
      wj["tour"] = {{"length_m", tour.length},
                    {"rooms", tour.visited.size()},
                    {"seg_precision", tour_score.segmentation.precision},
                    {"seg_recall", tour_score.segmentation.recall}};
      // The cap: cap_factor x the tour's time at 0.5 m/s, at most --max-sim-s.
      job.cap_s = std::min(max_sim_s, std::max(600.0, cap_factor * tour.length / 0.5));
      wj["cap_s"] = job.cap_s;
      // People: the world's own, or walkers pacing stretches of the tour that wait for the robot
      // and step round it (as ./rgnav bench plan has them).
      rgnav::localize_eval::add_walkers(&world, tour.waypoints, walkers);
      for (auto& p : world.people)
        if (p.name.rfind("bench_walker_", 0) == 0) {
          p.personal_space = 0.4;
          p.patience = 5.0;
        }
      wj["people"] = world.people.size();
      job.truth = std::make_unique<ee::WorldTruth>(ee::world_truth(name, world, sim_options.robot));
      const ee::WorldTruth& wt = *job.truth;
      job.starts.push_back(ee::start_truth(wt, world.start, "fixed", sim_options.robot));
      for (int k = 0; k < starts; ++k) {
        const auto p = ee::random_standable(wt.raster, job.starts.front().area, wt.clearance, sim_options.robot.radius + 0.3, rng);
        if (!p) break;
        const double heading = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
        job.starts.push_back(ee::start_truth(wt, {p->x(), p->y(), heading}, "random" + std::to_string(k + 1), sim_options.robot));
      }
      wj["reachable_free_m2"] = job.starts.front().area.free_m2;
      wj["truth_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - world_t0).count();
      std::cerr << "explore bench: " << name << " tour " << wj["tour"].dump() << " cap " << job.cap_s << " s\n";
      world_jobs.push_back(std::move(job));
    }
    // The runs, on --jobs threads (each run is deterministic by itself).
    struct Task
    {
      size_t world, start;
      std::string method;
      json result;
    };
    std::vector<Task> tasks;
    for (size_t wi = 0; wi < world_jobs.size(); ++wi)
      for (size_t si = 0; si < world_jobs[wi].starts.size(); ++si)
        for (const auto& method : methods) tasks.push_back({wi, si, method, json()});
    std::atomic<size_t> next{0};
    std::mutex print;
    const auto worker = [&] {
      for (size_t k = next++; k < tasks.size(); k = next++) {
        Task& task = tasks[k];
        const WorldJob& job = world_jobs[task.world];
        const ee::StartTruth& st = job.starts[task.start];
        std::unique_ptr<ee::ExploreDriver> driver =
            task.method == "rgnav" ? ee::make_rg_driver(planner_options, explorer_options, map_period_s)
                                   : ee::make_frontier_driver(frontier, base_from_laser, planner_options.execution.max_speed);
        ee::RunSetup run_setup = setup;
        run_setup.max_sim_s = job.cap_s;
        const std::string dir = out_dir + "/" + job.name + "/" + st.label + "_" + task.method;
        const auto r = ee::run_exploration(*job.truth, st, *driver, run_setup, seed * 1000 + task.start, dir);
        json rj = ee::to_json(r);
        rj["world"] = job.name;
        rj["start_pose"] = {st.start.x, st.start.y, st.start.theta};
        rj["tour_length_m"] = st.tour_length_m;
        rj["length_vs_tour"] = st.tour_length_m > 0 ? json(r.driven_m / st.tour_length_m) : json(nullptr);
        if (std::isfinite(r.seg_precision)) rj["seg_precision_delta"] = r.seg_precision - job.tour_precision;
        json brief = rj;
        brief.erase("detail");
        {
          std::lock_guard<std::mutex> lock(print);
          std::cerr << "explore bench: " << brief.dump() << "\n";
        }
        task.result = std::move(rj);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < std::max(1, jobs); ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();

    for (size_t wi = 0; wi < world_jobs.size(); ++wi) {
      auto& job = world_jobs[wi];
      json& wj = job.wj;
      json runs = json::array();
      double wall = 0;
      for (const auto& task : tasks)
        if (task.world == wi) {
          runs.push_back(task.result);
          wall += task.result["wall_s"].get<double>();
        }
      // rgnav's length against the frontier explorer's from the same start.
      for (auto& r : runs) {
        if (r["method"] != "rgnav") continue;
        for (const auto& f : runs)
          if (f["method"] == "frontier" && f["start"] == r["start"] && f["driven_m"].get<double>() > 0)
            r["length_vs_frontier"] = r["driven_m"].get<double>() / f["driven_m"].get<double>();
      }
      wj["runs"] = runs;
      // Per world: the worst over its starts, per method.
      for (const auto& method : methods) {
        json m;
        m["rooms_entered_ratio"] = worst(runs, method, "rooms_entered_ratio", false);
        m["area_seen_ratio"] = worst(runs, method, "area_seen_ratio", false);
        int premature = 0, timeouts = 0;
        int64_t collisions = 0;
        for (const auto& r : runs)
          if (r["method"] == method) {
            premature += r["premature_end"].get<bool>();
            timeouts += r["timed_out"].get<bool>();
            collisions += r["collisions"].get<int64_t>();
          }
        m["premature_ends"] = premature;
        m["timeouts"] = timeouts;
        m["collisions"] = collisions;
        m["time_to_90_s_max"] = worst(runs, method, "time_to_90_s", true);
        m["time_s_max"] = worst(runs, method, "time_s", true);
        m["length_vs_tour"] = worst(runs, method, "length_vs_tour", true);
        m["seg_precision_delta"] = worst(runs, method, "seg_precision_delta", false);
        m["seg_precision"] = worst(runs, method, "seg_precision", false);
        m["seg_recall"] = worst(runs, method, "seg_recall", false);
        if (method == "rgnav") m["length_vs_frontier"] = worst(runs, method, "length_vs_frontier", true);
        wj[method] = m;
      }
      wj["runs_wall_s"] = wall;
      for (const auto& r : runs) all_runs.push_back(r);
      j["worlds"][job.name] = wj;
      std::filesystem::create_directories(out_dir + "/" + job.name);
      std::ofstream(out_dir + "/" + job.name + "/explore.json") << wj.dump(2) << "\n";
    }
    // The keys: worst over worlds (rgnav's explorer).
    const std::string m = "rgnav";
    j["rooms_entered_ratio"] = worst(all_runs, m, "rooms_entered_ratio", false);
    j["area_seen_ratio"] = worst(all_runs, m, "area_seen_ratio", false);
    int max_premature = 0;
    for (const auto& [name, wj] : j["worlds"].items())
      if (wj.contains(m)) max_premature = std::max(max_premature, wj[m]["premature_ends"].get<int>());
    j["premature_ends"] = max_premature;
    j["length_vs_frontier"] = worst(all_runs, m, "length_vs_frontier", true);
    j["length_vs_tour"] = worst(all_runs, m, "length_vs_tour", true);
    j["seg_precision_delta"] = worst(all_runs, m, "seg_precision_delta", false);
    // The same for the baseline, and totals.
    json base;
    base["rooms_entered_ratio"] = worst(all_runs, "frontier", "rooms_entered_ratio", false);
    base["area_seen_ratio"] = worst(all_runs, "frontier", "area_seen_ratio", false);
    base["length_vs_tour"] = worst(all_runs, "frontier", "length_vs_tour", true);
    base["seg_precision_delta"] = worst(all_runs, "frontier", "seg_precision_delta", false);
    j["frontier"] = base;
    json totals = json::object();
    for (const auto& method : methods) {
      int runs = 0, premature = 0, timeouts = 0;
      int64_t collisions = 0;
      for (const auto& r : all_runs)
        if (r["method"] == method) {
          ++runs;
          premature += r["premature_end"].get<bool>();
          timeouts += r["timed_out"].get<bool>();
          collisions += r["collisions"].get<int64_t>();
        }
      totals[method] = {{"runs", runs}, {"premature_ends", premature}, {"timeouts", timeouts}, {"collisions", collisions}};
    }
    j["totals"] = totals;
    j["timing"] = {{"wall_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - bench_t0).count()},
                   {"jobs", jobs},
                   {"max_sim_s", max_sim_s},
                   {"cap_factor", cap_factor},
                   {"starts_per_world", starts + 1}};
    j["seed"] = seed;
    j["spin_at_start_s"] = spin_s;
    j["vision_stand_in"] = !laser_only;
    j["targets"] = {{"rooms_entered_ratio", 1.0},  {"area_seen_ratio", 0.98},     {"premature_ends", 0},
                    {"length_vs_frontier", 0.8},   {"length_vs_tour", 1.5},       {"seg_precision_delta_min", -0.02}};
    const auto parent = std::filesystem::path(json_path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    std::ofstream(json_path) << j.dump(2) << "\n";
    json top;
    for (auto it = j.begin(); it != j.end(); ++it)
      if (it.key() != "worlds") top[it.key()] = it.value();
    std::cout << top.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "explore bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
