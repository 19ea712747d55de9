// ./rgnav bench localize: rgnav's localizer on maps built by rgnav's own pipeline, driven by the
// simulator with the config's odometry error and walking people, against the simulator's truth:
// tracking along the world's tour, global localization from random starts, kidnaps
// (localize_trials.h). Every drive is also written for MRPT's pf-localization
// (deploy/bench/mrpt), which the bench script runs beside it. The keys are described in
// deploy/bench/localize.sh.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "bench_stats.h"
#include "bench_world.h"
#include "config/finish_except.h"
#include "localize_trials.h"
#include "localizer/localizer.h"
#include "localizer/localizer_options.h"
#include "name_path_spec.h"
#include "runtime/process_main.h"
#include "sim/sim_options.h"

namespace rp = rgnav::rgmap_pipeline;
namespace le = rgnav::localize_eval;
namespace lo = rgnav::localizer;
using le::number_or_null;
using le::percentile;
using rgnav::geometry::Pose2;

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
    le::Totals totals;
    double max_bytes = 0;
    for (const auto& spec : sims) {
      const auto [name, path] = rp::split_spec(spec);
      const le::BenchWorld w = le::map_world(name, path, out_dir, sim_options, loaded, base_from_laser, walkers);
      nlohmann::json wj = le::map_quality(w);
      wj["world"] = path;
      lo::Localizer loc(loc_options);
      const auto t0 = std::chrono::steady_clock::now();
      loc.set_map(w.map);
      wj["map_load_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      max_bytes = std::max(max_bytes, static_cast<double>(loc.maps().bytes()));
      le::TrialContext ctx{sim_options, loc_options, rng, sim_options.start_utime, mrpt_scan_every};
      wj["tracking"] = le::run_tracking(w, loc, ctx, laps, totals);
      wj["global"] = le::run_global(w, loc, ctx, global_trials, mrpt_global, totals);
      wj["kidnap"] = le::run_kidnaps(w, loc, ctx, kidnaps, totals);
      j["worlds"][name] = wj;
      std::cerr << "localize bench: " << name << " " << wj.dump() << "\n";
    }

    double se = 0, st = 0;
    for (size_t k = 0; k < totals.track_xy.size(); ++k) {
      se += totals.track_xy[k] * totals.track_xy[k];
      st += totals.track_deg[k] * totals.track_deg[k];
    }
    const double n = std::max<double>(1, static_cast<double>(totals.track_xy.size()));
    j["tracking_updates"] = static_cast<int64_t>(totals.track_xy.size());
    j["tracking_rmse_m"] = std::sqrt(se / n);
    j["tracking_rmse_deg"] = std::sqrt(st / n);
    j["tracking_p95_m"] = number_or_null(percentile(totals.track_xy, 0.95));
    j["tracking_max_m"] = totals.track_xy.empty() ? 0.0 : *std::max_element(totals.track_xy.begin(), totals.track_xy.end());
    j["tracking_max_deg"] = totals.track_deg.empty() ? 0.0 : *std::max_element(totals.track_deg.begin(), totals.track_deg.end());
    j["handovers"] = totals.handovers;
    j["gateway_passed_events"] = totals.gateway_events;
    j["divergences"] = totals.divergences;
    j["false_kidnaps"] = totals.false_kidnaps;
    j["global_trials"] = totals.global_n;
    j["global_success_ratio"] = totals.global_n ? static_cast<double>(totals.global_ok) / static_cast<double>(totals.global_n) : 0.0;
    j["global_time_s_p50"] = number_or_null(percentile(totals.global_time, 0.5));
    // The estimate right (and staying so) within 10 s whether or not the localizer claims it yet,
    // and the trials in which it claimed a pose that was > 0.5 m wrong.
    j["global_estimate_success_ratio"] = totals.global_n ? static_cast<double>(totals.global_estimate_ok) / static_cast<double>(totals.global_n) : 0.0;
    j["global_wrong_claims"] = totals.global_wrong;
    // Trials that ended unsure where another place explains the robot's last views as well as
    // the true pose (the map repeats itself there), and the success ratio without them.
    j["global_ambiguous_trials"] = totals.global_ambiguous;
    j["global_success_ratio_unambiguous"] =
        totals.global_n > totals.global_ambiguous
            ? static_cast<double>(totals.global_ok) / static_cast<double>(totals.global_n - totals.global_ambiguous)
            : 0.0;
    // Every trial by its outcome (global_outcome.h), and the success ratio over the trials whose
    // views by the deadline single out the true pose (whether or not it was claimed).
    j["global_classes"] = totals.global_classes;
    const int64_t ambiguous_at_deadline = totals.global_classes.count("ambiguous_at_deadline") ? totals.global_classes.at("ambiguous_at_deadline") : 0;
    j["global_ambiguous_at_deadline_trials"] = ambiguous_at_deadline;
    j["global_success_ratio_distinguishable_at_deadline"] =
        totals.global_n > ambiguous_at_deadline
            ? static_cast<double>(totals.global_ok) / static_cast<double>(totals.global_n - ambiguous_at_deadline)
            : 0.0;
    j["global_travel_m_p50"] = number_or_null(percentile(totals.global_travel, 0.5));
    j["kidnap_trials"] = totals.kidnap_n;
    j["kidnap_flag_s_p50"] = number_or_null(percentile(totals.flag_time, 0.5));
    j["kidnap_flagged_ratio"] = totals.kidnap_n ? static_cast<double>(totals.flag_time.size()) / static_cast<double>(totals.kidnap_n) : 0.0;
    j["kidnap_recovered_ratio"] = totals.kidnap_n ? static_cast<double>(totals.kidnap_ok) / static_cast<double>(totals.kidnap_n) : 0.0;
    j["kidnap_recover_s_p50"] = number_or_null(percentile(totals.recover_time, 0.5));
    j["cpu_core_share"] = totals.cpu_s / std::max(1e-9, totals.sim_s);
    j["cpu_ms_per_update_p50"] = number_or_null(percentile(totals.update_cpu_ms, 0.5));
    j["global_cpu_ms_per_update_p50"] = number_or_null(percentile(totals.global_update_cpu_ms, 0.5));
    j["global_cpu_ms_per_update_p99"] = number_or_null(percentile(totals.global_update_cpu_ms, 0.99));
    j["particles_mean"] = totals.updates ? static_cast<double>(totals.particles_sum) / static_cast<double>(totals.updates) : 0.0;
    j["map_memory_mb_max"] = max_bytes / 1e6;
    // (a bare file name has no parent, and create_directories("") throws)
    if (const auto parent = std::filesystem::path(json_path).parent_path(); !parent.empty()) std::filesystem::create_directories(parent);
    std::ofstream(json_path) << j.dump(2) << "\n";
    std::cout << j.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "localize bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
