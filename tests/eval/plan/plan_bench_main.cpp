// ./rgnav bench plan: rgnav's planner (procs/planner) on maps built by rgnav's own pipeline,
// (1) planning alone: random start/goal pairs against the exact shortest path and a whole-building
// grid A* on the same occupancy (plan_pairs.h), and (2) closed loop in the simulator with
// collision avoidance, the lld and walking people (closed_loop.h). The keys are described in
// deploy/bench/plan.sh.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "bench_stats.h"
#include "bench_world.h"
#include "closed_loop.h"
#include "collision_avoidance/ca_options.h"
#include "config/finish_except.h"
#include "lld/lld_options.h"
#include "name_path_spec.h"
#include "occupancy_grid.h"
#include "plan_pairs.h"
#include "planner/planner_options.h"
#include "runtime/process_main.h"
#include "sim/sim_options.h"

namespace rp = rgnav::rgmap_pipeline;
namespace le = rgnav::localize_eval;
namespace pe = rgnav::plan_eval;
using le::number_or_null;

int main(int argc, char** argv)
{
  CLI::App app{"Planning benchmark: rgnav's planner on its own maps of simulated worlds, alone and in closed loop"};
  const std::string cfg_dir = rgnav::runtime::default_config_dir();
  rp::PipelineConfigPaths paths{cfg_dir + "/scan_mapper.yaml", cfg_dir + "/gateway_detector_aligned.yaml", cfg_dir + "/rg_kernel.yaml",
                                cfg_dir + "/robot.yaml"};
  std::string sim_config = cfg_dir + "/sim.yaml", planner_config = cfg_dir + "/planner.yaml", lld_config = cfg_dir + "/lld.yaml",
              ca_config = cfg_dir + "/collision_avoidance.yaml", json_path, out_dir;
  std::vector<std::string> sims, closed_loop_worlds;
  pe::PairsOptions pairs;
  pe::ClosedLoopOptions loop;
  int walkers = 3;
  double reference_resolution = 0.05;
  uint64_t seed = 7;
  app.add_option("--planner-config", planner_config, "planner config")->check(CLI::ExistingFile);
  app.add_option("--lld-config", lld_config, "lld config (closed loop)")->check(CLI::ExistingFile);
  app.add_option("--ca-config", ca_config, "collision avoidance config (closed loop)")->check(CLI::ExistingFile);
  app.add_option("--config", paths.scan_mapper, "scan mapper config (mapping)")->check(CLI::ExistingFile);
  app.add_option("--gateway-config", paths.gateway_detector, "gateway detector config (mapping)")->check(CLI::ExistingFile);
  app.add_option("--rg-config", paths.rg_kernel, "RG kernel config (mapping)")->check(CLI::ExistingFile);
  app.add_option("--robot", paths.robot, "robot description")->check(CLI::ExistingFile);
  app.add_option("--sim-config", sim_config, "simulator config (odometry error, laser)")->check(CLI::ExistingFile);
  app.add_option("--sim", sims, "NAME=WORLD (world file or IPA map image), repeatable")->required();
  app.add_option("--closed-loop", closed_loop_worlds, "NAME of a --sim world also driven in closed loop, repeatable");
  app.add_option("--pairs", pairs.pairs, "start/goal pairs per world")->check(CLI::Range(0, 100000));
  app.add_option("--region-pairs", pairs.region_pairs, "region paths timed per world")->check(CLI::Range(0, 100000));
  app.add_option("--pictures", pairs.pictures, "routes drawn per world into <out>/<world>/routes.png")->check(CLI::Range(0, 1000));
  app.add_option("--goals", loop.goals, "closed-loop goals per world")->check(CLI::Range(0, 10000));
  app.add_option("--door-cases", loop.door_cases, "closed-door cases per closed-loop world")->check(CLI::Range(0, 100));
  app.add_option("--reference-resolution", reference_resolution, "cell edge of the whole-building grid [m]")
      ->check(CLI::Range(0.01, 0.5));
  app.add_option("--walkers", walkers, "people added to a world that has none")->check(CLI::Range(0, 20));
  app.add_option("--seed", seed, "random pairs, goals and simulator seeds");
  app.add_option("--json", json_path, "output JSON")->required();
  app.add_option("--out", out_dir, "folder for maps and pictures")->required();
  CLI11_PARSE(app, argc, argv);
  loop.trace = std::getenv("PLAN_TRACE") != nullptr;
  spdlog::set_level(spdlog::level::warn);
  try {
    for (const auto& name : closed_loop_worlds)
      if (std::none_of(sims.begin(), sims.end(), [&](const std::string& s) { return rp::split_spec(s).first == name; }))
        throw std::runtime_error("--closed-loop " + name + ": no --sim of that name");
    const rp::LoadedPipeline loaded = rp::load_pipeline(paths);
    const pe::DriveChainOptions chain = pe::load_drive_chain({sim_config, planner_config, lld_config, ca_config}, loaded.robot);
    const auto& planner_options = chain.planner;
    const auto& sim_options = chain.sim;
    const pe::ClosedLoopSetup setup{chain.planner, chain.lld, chain.ca, chain.sim};

    std::mt19937_64 rng(seed);
    nlohmann::json j;
    j["planner_config"] = planner_config;
    j["planner_resolution_m"] = planner_options.grid.resolution;
    j["reference_resolution_m"] = reference_resolution;
    j["seed"] = seed;
    pe::PairSamples pair_totals;
    pe::ClosedLoopSamples loop_totals;
    for (const auto& spec : sims) {
      const auto [name, path] = rp::split_spec(spec);
      auto t0 = std::chrono::steady_clock::now();
      le::BenchWorld w = le::map_world(name, path, out_dir, sim_options, loaded, loaded.robot.laser_front.base_from_laser, walkers);
      // The people added for the benchmark behave like the office world's: they wait 0.4 m from
      // a robot they walk toward and step round it after 5 s.
      for (auto& p : w.world.people)
        if (p.name.rfind("bench_walker_", 0) == 0) {
          p.personal_space = 0.4;
          p.patience = 5.0;
        }
      nlohmann::json wj;
      wj["world"] = path;
      wj["map"] = le::map_quality(w);
      wj["map"]["mapping_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      t0 = std::chrono::steady_clock::now();
      const pe::ConfigSpace space(pe::compose_occupancy(w.map, reference_resolution, planner_options.grid.passage_depth),
                                  planner_options.grid.robot_radius);
      wj["map"]["grid_cells"] = space.grid().width * space.grid().height;
      wj["map"]["grid_origin"] = {space.grid().origin.x(), space.grid().origin.y()};   // routes.png's lower-left corner
      wj["map"]["grid_m"] = {space.grid().width * space.grid().resolution, space.grid().height * space.grid().resolution};
      wj["map"]["grid_build_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      wj["planning"] = pe::run_pairs(name, w.map, planner_options, space, pairs, rng, w.dir, &pair_totals);
      std::cerr << "plan bench: " << name << " planning " << wj["planning"].dump() << "\n";
      if (std::find(closed_loop_worlds.begin(), closed_loop_worlds.end(), name) != closed_loop_worlds.end()) {
        wj["closed_loop"] = pe::run_closed_loop(w, space, setup, loop, rng, &loop_totals);
        nlohmann::json brief = wj["closed_loop"];
        brief.erase("goal_log");
        std::cerr << "plan bench: " << name << " closed loop " << brief.dump() << "\n";
      }
      j["worlds"][name] = wj;
      std::ofstream(w.dir + "/plan.json") << wj.dump(2) << "\n";
    }

    const nlohmann::json p = pair_totals.summary(planner_options);
    const nlohmann::json c = loop_totals.summary();
    // The keys first.
    j["pairs"] = p["pairs"];
    j["success_ratio"] = p["success_ratio"];
    j["global_ms_p50"] = p["global_ms_p50"];
    j["region_ms_p50"] = p["region_ms_p50"];
    j["region_ms_p99"] = p["region_ms_p99"];
    j["length_ratio_p50"] = p["length_ratio_p50"];
    j["length_ratio_max"] = p["length_ratio_max"];
    j["clearance_min_m"] = p["clearance_min_m"];
    j["grid_astar_ms_p50"] = p["grid_astar_ms_p50"];
    j["speedup_vs_grid"] = p["speedup_vs_grid"];
    j["closed_loop_goals"] = c["goals"];
    j["closed_loop_success_ratio"] = c["success_ratio"];
    j["closed_loop_collisions"] = c["collisions"];
    j["spl"] = c["spl"];
    j["planning"] = p;
    j["closed_loop"] = c;
    j["targets"] = {{"success_ratio", 1.0},          {"global_ms_p50_max", 1.0},   {"region_ms_p50_max", 10.0},
                    {"region_ms_p99_max", 50.0},      {"length_ratio_max", 1.05},   {"clearance_wanted_m", p["clearance_wanted_m"]},
                    {"speedup_vs_grid_min", 5.0},     {"closed_loop_success_ratio", 0.98},
                    {"closed_loop_collisions", 0},    {"spl_min", 0.9}};
    if (!json_path.empty()) {
      const auto parent = std::filesystem::path(json_path).parent_path();
      if (!parent.empty()) std::filesystem::create_directories(parent);
      std::ofstream(json_path) << j.dump(2) << "\n";
    }
    nlohmann::json top;
    for (auto it = j.begin(); it != j.end(); ++it)
      if (!it.value().is_object()) top[it.key()] = it.value();
    std::cout << top.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "plan bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
