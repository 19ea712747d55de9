// rgnav_slam_bench: the SLAM benchmark (see deploy/bench/slam.sh).
//   rgnav_slam_bench --json OUT.json --maps DIR [--config FILE]
//     [--real NAME=LOG[@X,Y,THETA][#SECONDS]] ... [--sim NAME=WORLD ... --sim-config sim.yaml]
//     [--sim-people NAME=WORLD ...] [--sim-seeds 1,2,3] [--sim-random NAME=MAP.png ...]
// Per real log: agreement with the log's REFERENCE_POSE poses (relations metric, when
// present), map consistency, realtime factor (log duration / CPU time of the mapping on one
// core; #SECONDS gives the true duration of a log whose timestamps are synthetic).
// Per simulated world: the relations metric and ATE against the simulator's exact truth, for
// the simulator config's seed (sim.<world>) and, with --sim-seeds, for each of those seeds
// (sim_seeds.<world>: per seed, their mean and worst): one seed's odometry noise can happen
// to hide or provoke an error, so robustness is judged over several. --sim-people drives the
// same tour with the world's people walking (the robot's body passes through them): moving
// legs in the scans. --sim-random drives generated buildings (tests/eval/buildings) with the
// config's seed only (many buildings stand in for many seeds); a building without a tour is
// reported with its error rather than ending the bench. Top level: random_buildings, and
// broken_maps / broken_map_list: simulated runs (sim.*, named and generated) whose estimate fits
// the true poses, after the best rigid fit, with an RMSE (ate_rmse_m) above 0.3 m.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "config/finish_except.h"
#include "importers/lcm_log_io.h"
#include "offline_mapping.h"
#include "offline_options.h"
#include "runtime/process_main.h"
#include "scan_mapper/relations_metric.h"
#include "scan_mapper/scan_mapper_options.h"
#ifdef RGNAV_SLAM_BENCH_SIM
#include "building_files.h"
#include "sim/sim_options.h"
#include "sim/world_yaml.h"
#include "sim_mapping.h"
#endif

namespace sm = rgnav::scan_mapper;

namespace {

// A map whose accepted scans fit their true poses, after the best rigid fit, worse than this is
// broken (issue 33; as the RG map bench's kBrokenMapRmseM).
constexpr double kBrokenMapRmseM = 0.3;

// The scan mapper's counters that the real logs and the simulated worlds both report (a JSON
// object's keys are sorted, so where they are added does not change the output).
void add_mapper_stats(const sm::MapperStats& s, nlohmann::json* j)
{
  auto& o = *j;
  o["accepted_scans"] = s.accepted;
  o["loop_closures"] = s.loop_closures;
  o["loop_attempts"] = s.loop_attempts;
  o["loop_rejected_after_optimisation"] = s.loop_rejected_after_opt;
  o["loop_rejected_strain"] = s.loop_rejected_strain;
  o["loop_ambiguous"] = s.loop_ambiguous;
  o["loop_pruned"] = s.loop_pruned;
  o["correlative_retries"] = s.correlative_retries;
  o["turns_held"] = s.turns_held;
  o["axes_held"] = s.axes_held;
  o["odometry_trans_scale"] = s.odometry_trans_scale;
  o["odometry_scale"] = s.odometry_scale;
}

struct RealLog
{
  std::string name, path;
  std::optional<sm::Pose2> mount;
  double true_seconds = 0.0;  // > 0: the recording's real duration (synthetic timestamps)
};

RealLog parse_real(const std::string& spec)
{
  RealLog r;
  const auto eq = spec.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("--real wants NAME=LOG[@X,Y,THETA]: " + spec);
  r.name = spec.substr(0, eq);
  r.path = spec.substr(eq + 1);
  const auto hash = r.path.find('#');
  if (hash != std::string::npos) {
    r.true_seconds = std::stod(r.path.substr(hash + 1));
    r.path = r.path.substr(0, hash);
  }
  const auto at = r.path.find('@');
  if (at != std::string::npos) {
    double x, y, th;
    if (std::sscanf(r.path.substr(at + 1).c_str(), "%lf,%lf,%lf", &x, &y, &th) != 3)
      throw std::invalid_argument("bad mounting pose in " + spec);
    r.mount = sm::Pose2{x, y, th};
    r.path = r.path.substr(0, at);
  }
  return r;
}

nlohmann::json evaluate_real(const RealLog& spec, sm::ScanMapperOptions options, const std::string& maps_dir)
{
  if (spec.mount) options.base_from_laser = *spec.mount;
  const auto log = rgnav::importers::read_lcm_log(spec.path);
  const auto r = sm::run_offline(log, options);
  const double consistency = sm::write_outputs(r, options, maps_dir + "/" + spec.name);
  nlohmann::json j;
  j["consistency"] = consistency;
  const auto factor = [&](double seconds) { return r.cpu_seconds > 0 ? seconds / r.cpu_seconds : 0.0; };
  j["log_seconds"] = r.log_seconds;
  if (spec.true_seconds > 0) {
    // The log's timestamps are synthetic: its duration is the recording's, which the headline
    // factor is taken on (as Hess et al. take theirs); the timestamps' own factor beside it.
    j["realtime_factor"] = factor(spec.true_seconds);
    j["true_log_seconds"] = spec.true_seconds;
    j["realtime_factor_synthetic_timestamps"] = factor(r.log_seconds);
  } else {
    j["realtime_factor"] = factor(r.log_seconds);
  }
  j["cpu_seconds"] = r.cpu_seconds;
  j["scans"] = r.stats.scans_in;
  j["matched_scans"] = r.stats.matched;
  j["match_rejected"] = r.stats.match_rejected;
  add_mapper_stats(r.stats, &j);
  j["map_png"] = maps_dir + "/" + spec.name + "/map.png";
  if (!log.reference.empty()) {
    std::map<int64_t, const sm::ScanEstimate*> by_id;
    for (const auto& s : r.scans) by_id[s.scan_id] = &s;
    std::vector<sm::TimedPose> ref;
    std::vector<sm::Pose2> ref_poses, est;
    std::vector<int64_t> ref_ids;
    for (const auto& p : log.reference) {
      auto it = by_id.find(p.seq);
      if (it == by_id.end()) continue;
      ref_ids.push_back(p.seq);
      ref.push_back({p.utime, sm::Pose2{p.x, p.y, sm::normalize_angle(p.theta)}});
      ref_poses.push_back(ref.back().pose);
      est.push_back(it->second->map_from_base);
    }
    const auto rel = sm::select_relations(ref);
    const auto err = sm::relation_error(est, ref_poses, rel);
    // The pairs behind the figures, for looking into where the disagreement is.
    std::ofstream pairs(maps_dir + "/" + spec.name + "/reference_pairs.txt");
    pairs << "# scan_id utime_us ref_x ref_y ref_theta est_x est_y est_theta\n";
    for (size_t k = 0; k < ref.size(); ++k)
      pairs << ref_ids[k] << ' ' << ref[k].utime << ' ' << ref_poses[k].x() << ' '
            << ref_poses[k].y() << ' ' << ref_poses[k].theta() << ' ' << est[k].x() << ' ' << est[k].y() << ' ' << est[k].theta() << '\n';
    j["ref_poses"] = ref.size();
    j["ref_relations"] = err.count;
    j["ref_trans_mean_m"] = err.trans_mean_m;
    j["ref_trans_std_m"] = err.trans_std_m;
    j["ref_rot_mean_deg"] = err.rot_mean_deg;
    j["ref_rot_std_deg"] = err.rot_std_deg;
    j["ref_ate_rmse_m"] = sm::ate_rmse(est, ref_poses);
  }
  return j;
}

#ifdef RGNAV_SLAM_BENCH_SIM
nlohmann::json evaluate_sim(const std::string& spec, const rgnav::sim::SimulatorOptions& sim_options,
                            const sm::ScanMapperOptions& options, const sm::SimMappingOptions& sim_mapping,
                            const std::string& maps_dir, const std::string& suffix, std::string* name)
{
  const auto eq = spec.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("--sim wants NAME=WORLD: " + spec);
  *name = spec.substr(0, eq);
  const auto r = sm::run_sim_mapping(spec.substr(eq + 1), sim_options, options, sm::SimMappingOptions(sim_mapping));
  sm::OfflineResult off;
  off.nodes = r.nodes;
  sm::ScanMapperOptions written = options;
  written.base_from_laser = sm::Pose2{sim_options.laser.mount_x, sim_options.laser.mount_y, sim_options.laser.mount_yaw};
  nlohmann::json j;
  j["world"] = spec.substr(eq + 1);
  j["seed"] = sim_options.seed;
  const std::string dir = maps_dir + "/sim_" + *name + suffix;
  j["consistency"] = sm::write_outputs(off, written, dir);
  // Estimate next to truth at every accepted scan, for looking into where errors arise.
  sm::write_truth_pairs(dir + "/truth_pairs.txt", r.nodes, r.truth, &r.online, &r.loop_closed_at);
  {
    // Every loop closure of the final graph against the truth, to find the false ones.
    std::ofstream closures(dir + "/closures.txt");
    closures << "# from to err_x err_y err_theta chi2_at_truth sigma_max_m (err: edge error at the true poses)\n";
    for (const auto& c : r.closures)
      closures << c.from << ' ' << c.to << ' ' << c.error_at_truth.x() << ' ' << c.error_at_truth.y() << ' '
               << c.error_at_truth.z() << ' ' << c.chi2_at_truth << ' ' << c.sigma_max_m << '\n';
  }
  j["trans_mean_m"] = r.relations.trans_mean_m;
  j["trans_std_m"] = r.relations.trans_std_m;
  j["rot_mean_deg"] = r.relations.rot_mean_deg;
  j["rot_std_deg"] = r.relations.rot_std_deg;
  j["relations"] = r.relations.count;
  j["ate_rmse_m"] = r.ate_rmse_m;
  j["odometry_ate_rmse_m"] = r.odometry_ate_rmse_m;
  j["realtime_factor"] = r.mapping_cpu_seconds > 0 ? r.sim_seconds / r.mapping_cpu_seconds : 0.0;
  j["sim_seconds"] = r.sim_seconds;
  j["mapping_cpu_seconds"] = r.mapping_cpu_seconds;
  j["simulator_cpu_seconds"] = r.sim_cpu_seconds;
  j["tour_length_m"] = r.tour_length_m;
  j["laps"] = r.laps;
  j["driven_m"] = r.driven_m;
  j["capped"] = r.capped;
  j["people_removed"] = r.people_removed;
  j["people_walking"] = r.people_walking;
  if (r.capped) j["cap_sim_seconds"] = sim_mapping.max_sim_s;
  j["collisions"] = r.collisions;
  j["loop_closures_wrong"] = r.loop_closures_wrong;
  j["loop_closures_inconsistent"] = r.loop_closures_inconsistent;
  add_mapper_stats(r.stats, &j);
  return j;
}

std::vector<uint64_t> parse_seeds(const std::string& list)
{
  std::vector<uint64_t> seeds;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) continue;
    size_t used = 0;
    const unsigned long long v = std::stoull(item, &used);
    if (used != item.size()) throw std::invalid_argument("--sim-seeds wants a comma-separated list of integers: " + list);
    seeds.push_back(v);
  }
  return seeds;
}

// The figures of one world over several seeds: each seed's, their mean and the worst.
nlohmann::json summarize_seeds(const std::vector<nlohmann::json>& runs)
{
  static const char* const kKeys[] = {"trans_mean_m", "rot_mean_deg", "ate_rmse_m", "realtime_factor"};
  nlohmann::json out;
  for (const auto& r : runs) {
    nlohmann::json one;
    for (const char* k : kKeys) one[k] = r[k];
    one["capped"] = r["capped"];
    one["loop_closures"] = r["loop_closures"];
    out["per_seed"][std::to_string(r["seed"].get<uint64_t>())] = std::move(one);
  }
  for (const char* k : kKeys) {
    double sum = 0.0, worst = 0.0;
    bool first = true;
    for (const auto& r : runs) {
      const double v = r[k].get<double>();
      sum += v;
      // Worst: the largest error, the smallest realtime factor.
      const bool higher_is_better = std::string(k) == "realtime_factor";
      if (first || (higher_is_better ? v < worst : v > worst)) worst = v;
      first = false;
    }
    out[std::string("mean_") + k] = runs.empty() ? 0.0 : sum / static_cast<double>(runs.size());
    out[std::string("worst_") + k] = worst;
  }
  out["seeds"] = runs.size();
  return out;
}
#endif

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"SLAM benchmark of the scan mapper"};
  std::string json_path, maps_dir, config_path = rgnav::runtime::default_config_dir() + "/scan_mapper.yaml", robot_path;
  std::vector<std::string> reals;
  app.add_option("--json", json_path, "result file")->required();
  app.add_option("--maps", maps_dir, "folder for maps and trajectories")->required();
  app.add_option("--real", reals, "NAME=LOG[@X,Y,THETA] (laser mounting pose of that robot)");
  app.add_option("--config", config_path, "scan mapper config (one parameter set for everything)");
  app.add_option("--robot", robot_path, "robot description (default: robot.yaml beside the config)");
  std::vector<std::string> sims;
  std::string sim_config = rgnav::runtime::default_config_dir() + "/sim.yaml";
#ifdef RGNAV_SLAM_BENCH_SIM
  sm::SimMappingOptions sim_mapping;
  app.add_option("--sim", sims, "NAME=WORLD: drive a closed tour in this simulated world (exact ground truth)");
  std::vector<std::string> sims_with_people;
  app.add_option("--sim-people", sims_with_people,
                 "NAME=WORLD: as --sim, with the world's people walking (seen by the laser; the robot passes through them)");
  app.add_option("--sim-config", sim_config, "simulator config (robot, drive, odometry error, laser)");
  app.add_option("--sim-laps", sim_mapping.laps, "laps of the planned tour")->check(CLI::Range(1, 100));
  app.add_option("--sim-max-s", sim_mapping.max_sim_s, "cap on simulated seconds per world")->check(CLI::PositiveNumber);
  std::string seed_list;
  app.add_option("--sim-seeds", seed_list, "comma-separated simulator seeds: every world is also run with each");
  std::vector<std::string> random_sims;
  app.add_option("--sim-random", random_sims,
                 "NAME=MAP.png: a generated building (rgnav_building_gen), driven as --sim with the config's seed only");
#endif
  CLI11_PARSE(app, argc, argv);
  try {
    if (robot_path.empty()) robot_path = rgnav::runtime::default_robot_path(config_path);
    const auto robot = rgnav::config::load_robot_description_file(robot_path);
    const auto options = sm::load_offline_options(config_path, robot);
    nlohmann::json out;
    out["config"] = config_path;
    for (const auto& spec : reals) {
      const auto r = parse_real(spec);
      std::cerr << "real log " << r.name << ": " << r.path << "\n";
      out["real"][r.name] = evaluate_real(r, options, maps_dir);
      std::cerr << out["real"][r.name].dump(2) << "\n";
    }
#ifdef RGNAV_SLAM_BENCH_SIM
    if (!sims.empty() || !sims_with_people.empty() || !random_sims.empty()) {
      const auto sim_cfg = rgnav::config::Config::load(sim_config);
      const auto sim_options = rgnav::sim::load_simulator_options(sim_cfg, robot);
      rgnav::config::finish_except(sim_cfg, {"node", "channels", "sim", "protocol"});  // the process's own run settings
      const auto& e = sim_options.odometry;
      out["sim_config"] = sim_config;
      out["sim_odometry_error"] = {{"scale_translation", e.scale_translation},
                                   {"scale_rotation", e.scale_rotation},
                                   {"bias_rotation_per_m", e.bias_rotation_per_m},
                                   {"sigma_translation", e.sigma_translation},
                                   {"sigma_rotation", e.sigma_rotation},
                                   {"sigma_rotation_per_m", e.sigma_rotation_per_m}};
      const auto seeds = parse_seeds(seed_list);
      if (!seeds.empty()) out["sim_seed_list"] = seeds;
      std::vector<std::pair<std::string, bool>> worlds;  // spec, with people
      for (const auto& spec : sims) worlds.emplace_back(spec, false);
      for (const auto& spec : sims_with_people) worlds.emplace_back(spec, true);
      for (const auto& [spec, with_people] : worlds) {
        std::string name;
        auto world_mapping = sim_mapping;
        world_mapping.keep_people = with_people;
        std::cerr << "simulated world " << spec << " (seed " << sim_options.seed << ")\n";
        auto j = evaluate_sim(spec, sim_options, options, world_mapping, maps_dir, "", &name);
        std::cerr << j.dump(2) << "\n";
        if (!seeds.empty()) {
          std::vector<nlohmann::json> runs;
          for (const uint64_t seed : seeds) {
            if (seed == sim_options.seed) {
              runs.push_back(j);
              continue;
            }
            auto seeded = sim_options;
            seeded.seed = seed;
            std::cerr << "simulated world " << spec << " (seed " << seed << ")\n";
            runs.push_back(evaluate_sim(spec, seeded, options, world_mapping, maps_dir, "_seed" + std::to_string(seed), &name));
            std::cerr << runs.back().dump(2) << "\n";
          }
          out["sim_seeds"][name] = summarize_seeds(runs);
        }
        out["sim"][name] = std::move(j);
      }
      for (const auto& spec : random_sims) {
        std::string name = spec.substr(0, spec.find('='));
        std::cerr << "generated building " << spec << " (seed " << sim_options.seed << ")\n";
        nlohmann::json j;
        try {
          j = evaluate_sim(spec, sim_options, options, sim_mapping, maps_dir, "", &name);
        } catch (const std::exception& e) {
          // One building the tour planner cannot drive does not sink the rest.
          j = {{"world", spec.substr(spec.find('=') + 1)}, {"error", e.what()}};
        }
        j["random_building"] = true;
        std::cerr << name << ": ate_rmse_m " << j.value("ate_rmse_m", -1.0) << "\n";
        out["sim"][name] = std::move(j);
      }
    }
    {
      std::vector<std::string> maps;
      for (const auto& spec : random_sims) maps.push_back(spec.substr(spec.find('=') + 1));
      out["random_buildings"] = rgnav::buildings::count_buildings(maps);
    }
    out["broken_map_list"] = nlohmann::json::object();
    if (out.contains("sim"))
      for (const auto& [name, w] : out["sim"].items())
        if (w.value("ate_rmse_m", 0.0) > kBrokenMapRmseM) out["broken_map_list"][name] = w["ate_rmse_m"];
    out["broken_maps"] = out["broken_map_list"].size();
#else
    if (!sims.empty()) throw std::runtime_error("built without drivers/sim: no simulated part");
#endif
    std::ofstream f(json_path);
    f << out.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write " + json_path);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_slam_bench: " << e.what() << "\n";
    return 1;
  }
}
