// rgnav_rgmap_bench: evaluation of RG maps (./rgnav bench rgmap; key meanings in
// deploy/bench/rgmap.sh). Simulated tours with exact ground truth (--sim, and --sim-random for the
// generated buildings of tests/eval/buildings) and recorded logs with corrected poses (--real,
// counts only: no ground truth).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include "bench_summary.h"
#include "name_path_spec.h"
#include "building_files.h"
#include "config/finish_except.h"
#include "importers/lcm_log_io.h"
#include "offline_mapping.h"
#include "offline_run.h"
#include "rgmap_metrics.h"
#include "runtime/process_main.h"
#include "sim/sim_options.h"
#include "sim/world_yaml.h"
#include "sim_rgmap.h"

namespace rp = rgnav::rgmap_pipeline;

namespace {

// --diagnose: the ground-truth gateways missed and the false ones, and the room centres, all in
// the world frame, to find them on the pictures.
void print_gateway_diagnosis(const rp::WorldScore& score, const rp::GroundTruth& truth, const rgnav::rgmap::RgMap& map)
{
  // The map's gateways in gateway_positions' order, to name the false ones by id and class.
  std::vector<const rgnav::rgmap::Gateway*> counted;
  {
    const std::set<int64_t> repeats = rp::repeated_crossings(map);
    for (const auto& [id, g] : map.gateways()) {
      const auto& pts = g.gateway_points.empty() ? g.crossing_points : g.gateway_points;
      if (g.neutralized || repeats.count(id) || pts.empty() || !map.region(map.resolve(g.region_a))) continue;
      counted.push_back(&g);
    }
  }
  // Which ground-truth gateways were missed and where the false ones are (world frame).
  std::vector<char> t_hit(score.gateway_truth_positions.size(), 0), f_hit(score.gateway_found_positions.size(), 0);
  for (const auto& [t, f] : score.gateways.pairs) t_hit[static_cast<size_t>(t)] = f_hit[static_cast<size_t>(f)] = 1;
  for (size_t k = 0; k < t_hit.size(); ++k)
    if (!t_hit[k])
      std::cerr << "  missed gateway at (" << score.gateway_truth_positions[k].x() << ", "
                << score.gateway_truth_positions[k].y() << ")\n";
  // Room centres (world frame, cell centres), to find the rooms named above on the picture.
  std::vector<Eigen::Vector2d> sum(truth.room_names.size() + 1, Eigen::Vector2d::Zero());
  std::vector<int64_t> cnt(truth.room_names.size() + 1, 0);
  for (int y = 0; y < truth.rooms.height; ++y)
    for (int x = 0; x < truth.rooms.width; ++x)
      if (const int32_t l = truth.rooms.at(x, y); l > 0 && static_cast<size_t>(l) < sum.size()) {
        sum[static_cast<size_t>(l)] += Eigen::Vector2d(x, y);
        ++cnt[static_cast<size_t>(l)];
      }
  for (size_t l = 1; l < sum.size(); ++l)
    if (cnt[l] > 0) {
      const Eigen::Vector2d c = truth.rooms.origin + truth.rooms.resolution * (sum[l] / static_cast<double>(cnt[l]) + Eigen::Vector2d(0.5, 0.5));
      std::cerr << "  room " << truth.room_names[l - 1] << " centre (" << c.x() << ", " << c.y() << ")\n";
    }
  for (size_t k = 0; k < f_hit.size(); ++k) {
    if (f_hit[k]) continue;
    std::cerr << "  false gateway at (" << score.gateway_found_positions[k].x() << ", "
              << score.gateway_found_positions[k].y() << ")";
    if (k < counted.size())
      std::cerr << ": gateway " << counted[k]->id << " (" << rgnav::rgmap::to_string(counted[k]->cls) << ", "
                << counted[k]->gateway_points.size() << " points, regions " << counted[k]->region_a << ", "
                << counted[k]->region_b << ")";
    std::cerr << "\n";
  }
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Evaluate RG maps: simulated tours against ground truth, real logs by counts"};
  const std::string cfg_dir = rgnav::runtime::default_config_dir();
  rp::PipelineConfigPaths paths{cfg_dir + "/scan_mapper.yaml", cfg_dir + "/gateway_detector_aligned.yaml", cfg_dir + "/rg_kernel.yaml",
                                cfg_dir + "/robot.yaml"};
  std::string sim_config = cfg_dir + "/sim.yaml", json_path, out_dir;
  std::vector<std::string> sims, random_sims, people_sims, reals;
  rp::SimTourOptions tour;
  double match_m = 1.0;
  app.add_option("--config", paths.scan_mapper, "scan mapper config")->check(CLI::ExistingFile);
  app.add_option("--gateway-config", paths.gateway_detector, "gateway detector config")->check(CLI::ExistingFile);
  app.add_option("--rg-config", paths.rg_kernel, "RG kernel config")->check(CLI::ExistingFile);
  app.add_option("--robot", paths.robot, "robot description")->check(CLI::ExistingFile);
  app.add_option("--sim-config", sim_config, "simulator config (robot, odometry error, laser)")->check(CLI::ExistingFile);
  app.add_option("--sim", sims, "NAME=WORLD (world file or IPA map image), repeatable");
  app.add_option("--sim-random", random_sims,
                 "NAME=MAP.png: a generated building (rgnav_building_gen), as --sim, summarized apart, repeatable");
  app.add_option("--real", reals, "NAME=LOG.lcmlog with corrected poses as odometry (taken as given), repeatable");
  app.add_option("--laps", tour.laps, "tour laps per world")->check(CLI::Range(1, 10));
  app.add_option("--max-sim-s", tour.max_sim_s, "cap on simulated seconds per world")->check(CLI::Range(10.0, 36000.0));
  app.add_flag("--people", tour.people, "keep every world's walking people (seen by the laser; they and the robot pass through each other)");
  app.add_option("--sim-people", people_sims,
                 "NAME=WORLD: a world driven with its walking people kept (as --people), as --sim; its ghost_segments "
                 "add up to the top-level ghost_segments, repeatable");
  app.add_option("--gateway-match-m", match_m, "gateway positions closer than this match ground truth [m]")->check(CLI::Range(0.1, 5.0));
  app.add_option("--json", json_path, "output JSON")->required();
  app.add_option("--out", out_dir, "folder for the maps and pictures of every run")->required();
  bool verbose = false, diagnose = false, true_poses = false;
  app.add_flag("--true-poses", true_poses,
               "also map every world on the simulator's true poses (worlds_true_poses: segmentation without SLAM errors)");
  app.add_flag("--diagnose", diagnose,
               "print per region where its freespace falls outside its best room (and why), the missed gateways and the false "
               "ones (id, class, regions)");
  app.add_flag("--verbose", verbose, "log the libraries' progress messages (regions opened, merged, ...)");
  bool debug = false;
  app.add_flag("--debug", debug, "log the libraries' debug messages too (every gateway event the RG kernel gets, ...)");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(debug ? spdlog::level::debug : verbose ? spdlog::level::info : spdlog::level::warn);
  try {
    const rp::LoadedPipeline loaded = rp::load_pipeline(paths);
    nlohmann::json j;
    j["configs"] = {{"scan_mapper", paths.scan_mapper}, {"gateway_detector", paths.gateway_detector},
                    {"rg_kernel", paths.rg_kernel}, {"sim", sim_config}};
    j["gateway_classifier"] = loaded.classifier_note;
    j["gateway_match_m"] = match_m;
    j["laps"] = tour.laps;
    j["people"] = tour.people;
    j["worlds"] = nlohmann::json::object();
    if (true_poses) j["worlds_true_poses"] = nlohmann::json::object();
    j["logs"] = nlohmann::json::object();
    // Every simulated world with whether it is a generated building and whether its people walk.
    struct SimWorld
    {
      std::string spec;
      bool random_building = false;
      bool people = false;
    };
    std::vector<SimWorld> worlds;
    for (const auto& spec : sims) worlds.push_back({spec, false, tour.people});
    for (const auto& spec : random_sims) worlds.push_back({spec, true, tour.people});
    for (const auto& spec : people_sims) worlds.push_back({spec, false, true});
    // Ghost segments of the worlds driven with walking people (scan mapper poses): name -> count.
    nlohmann::json ghosts = nlohmann::json::object();
    int ghost_total = 0, ghost_segments_of = 0;
    {
      std::vector<std::string> maps;
      for (const auto& spec : random_sims) maps.push_back(rp::split_spec(spec).second);
      j["random_buildings"] = rgnav::buildings::count_buildings(maps);
    }
    if (!worlds.empty()) {
      const auto sim_cfg = rgnav::config::Config::load(sim_config);
      const auto sim_options = rgnav::sim::load_simulator_options(sim_cfg, loaded.robot);
      rgnav::config::finish_except(sim_cfg, {"node", "channels", "sim", "protocol"});  // the process's own run settings
      for (const auto& [spec, random_building, people] : worlds) {
        const auto [name, path] = rp::split_spec(spec);
        // The headline on the scan mapper's poses; on request again on the true poses.
        for (const bool on_truth : {false, true}) {
          if (on_truth && !true_poses) break;
          const char* section = on_truth ? "worlds_true_poses" : "worlds";
          const std::string label = on_truth ? name + " (true poses)" : name;
          try {
            const auto world = rgnav::sim::load_world(path);
            const auto truth = rp::ground_truth_of(world);
            const rp::StaticSurfaces statics(world, sim_options.laser.mount_height);
            auto options = tour;
            options.true_poses = on_truth;
            options.people = people;
            const auto run = rp::run_sim_rgmap(world, sim_options, loaded, options);
            const auto score = rp::score_world(run, truth, match_m, &statics);
            auto w = rp::to_json(run, score);
            w["world"] = path;
            w["poses"] = on_truth ? "true" : "scan_mapper";
            w["people"] = people ? static_cast<int>(world.people.size()) : 0;
            if (random_building) w["random_building"] = true;
            if (people && !on_truth && !world.people.empty()) {
              ghosts[name] = score.ghosts.ghosts;
              ghost_total += score.ghosts.ghosts;
              ghost_segments_of += score.ghosts.segments;
            }
            const std::string dir = out_dir + "/" + name + (on_truth ? "/true_poses" : "");
            rp::write_run_outputs(run.run, loaded.options, dir);
            rgnav::scan_mapper::write_truth_pairs(dir + "/truth_pairs.txt", run.run.nodes, run.truth_at_node);
            w["pictures"] = {dir + "/rgmap.svg", dir + "/rgmap.png"};
            j[section][name] = w;
            if (diagnose) {
              std::cerr << label << ":\n" << rp::to_text(score.segmentation_diagnosis, truth.room_names);
              print_gateway_diagnosis(score, truth, run.run.map);
              for (const auto& [a, b] : score.ghosts.ghost_list)
                std::cerr << "  ghost segment (" << a.x() << ", " << a.y() << ") - (" << b.x() << ", " << b.y() << ")\n";
            }
            std::cerr << label << ": precision " << w["seg_precision"] << " recall " << w["seg_recall"] << " gateways "
                      << w["gateways_matched"] << "/" << w["gateways_truth"] << " false " << w["gateways_false"]
                      << " isomorphic " << w["graph_isomorphic"] << " ghost segments " << w["ghost_segments"] << "/"
                      << w["segments"] << "\n";
          } catch (const std::exception& e) {
            // One world that cannot be run (no tour through it, unreadable) does not sink the rest.
            j[section][name] = {{"world", path}, {"error", e.what()}};
            if (random_building) j[section][name]["random_building"] = true;
            std::cerr << label << ": " << e.what() << "\n";
          }
        }
      }
    }
    j["summary"] = nlohmann::json::object();
    for (const char* section : {"worlds", "worlds_true_poses"})
      if (j.contains(section)) j["summary"][section] = rp::summarize_ipa_worlds(j[section]);
    // Maps the scan mapper broke (rigid-fit RMSE of the accepted scans above the threshold), named
    // worlds and generated buildings alike; the true-pose runs have no SLAM to break.
    j["broken_map_list"] = rp::broken_maps(j["worlds"]);
    j["broken_maps"] = j["broken_map_list"].size();
    // Issue 33: only the static structure in the map, counted where people walk.
    j["ghost_segments"] = ghost_total;
    j["ghost_segments_segments"] = ghost_segments_of;
    j["ghost_segment_worlds"] = ghosts;
    for (const auto& spec : reals) {
      const auto [name, path] = rp::split_spec(spec);
      auto given = loaded;
      given.options.poses_as_given = true;
      given.options.mapper.base_from_laser = rgnav::geometry::Pose2();   // the corrected logs' scans are in the robot frame
      const auto log = rgnav::importers::read_lcm_log(path);
      const auto run = rp::run_pipeline(log, given);
      const std::string dir = out_dir + "/" + name;
      auto s = rp::write_run_outputs(run, given.options, dir);
      s["false_positives"] = nullptr;   // no ground truth for these logs
      s["log"] = path;
      s["pictures"] = {dir + "/rgmap.svg", dir + "/rgmap.png"};
      j["logs"][name] = s;
      std::cerr << name << ": " << s["regions"] << " regions, " << s["gateways"] << " gateways, compression " << s["compression"] << "\n";
    }
    std::filesystem::create_directories(std::filesystem::path(json_path).parent_path());
    std::ofstream f(json_path);
    f << j.dump(1) << "\n";
    if (!f) throw std::runtime_error("cannot write " + json_path);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_rgmap_bench: " << e.what() << "\n";
    return 1;
  }
}
