// rgnav_rgmap_offline: scan mapper + gateway detector + RG kernel over an LCM log
// (LASER_FRONT + ODOMETRY), in one thread on message time (./rgnav map).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <iostream>

#include "importers/log_to_map.h"
#include "offline_run.h"
#include "runtime/process_main.h"

namespace rp = rgnav::rgmap_pipeline;

int main(int argc, char** argv)
{
  CLI::App app{"Build an RG map offline from an LCM log (scan mapper + gateway detector + RG kernel)"};
  const std::string cfg_dir = rgnav::runtime::default_config_dir();
  std::string log_path, out;
  rp::PipelineConfigPaths paths{cfg_dir + "/scan_mapper.yaml", cfg_dir + "/gateway_detector_aligned.yaml", cfg_dir + "/rg_kernel.yaml",
                                cfg_dir + "/robot.yaml"};
  std::vector<double> mount;
  bool given = false, no_pictures = false;
  rp::OutputOptions oo;
  app.add_option("log", log_path, "LCM log with LASER_FRONT and ODOMETRY")->required()->check(CLI::ExistingFile);
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--config", paths.scan_mapper, "scan mapper config")->check(CLI::ExistingFile);
  app.add_option("--gateway-config", paths.gateway_detector, "gateway detector config")->check(CLI::ExistingFile);
  app.add_option("--rg-config", paths.rg_kernel, "RG kernel config")->check(CLI::ExistingFile);
  app.add_option("--robot", paths.robot, "robot description")->check(CLI::ExistingFile);
  app.add_option("--base-from-laser", mount, "laser mounting pose of the logged robot: x y theta [m m rad]")->expected(3);
  app.add_flag("--poses-as-given", given, "take the log's odometry as corrected poses (no scan matching)");
  app.add_option("--pixels-per-metre", oo.pixels_per_metre, "RG map picture scale")->check(CLI::Range(1.0, 500.0));
  app.add_option("--export-resolution", oo.export_resolution, "map_server export cell size [m]")->check(CLI::Range(0.01, 1.0));
  app.add_flag("--no-pictures", no_pictures, "skip rgmap.svg/.png and the map_server export");
  bool verbose = false;
  app.add_flag("--verbose", verbose, "log the libraries' progress messages (regions opened, merged, ...)");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(verbose ? spdlog::level::info : spdlog::level::warn);
  oo.pictures = !no_pictures;
  rp::LoadedPipeline loaded;
  try {
    loaded = rp::load_pipeline(paths);
  } catch (const std::exception& e) {
    std::cerr << "rgnav_rgmap_offline: " << e.what() << "\n";
    return 2;
  }
  if (mount.size() == 3)
    loaded.options.mapper.base_from_laser = rgnav::geometry::Pose2(mount[0], mount[1], mount[2]);
  loaded.options.poses_as_given = given;
  try {
    const auto log = rgnav::importers::read_log_to_map(log_path, "rgnav_rgmap_offline");
    if (!log) return 1;
    const auto run = rp::run_pipeline(*log, loaded);
    const auto s = rp::write_run_outputs(run, loaded.options, out, oo);
    std::cout << log_path << ": " << s["scans"] << " scans, " << s["accepted_scans"] << " accepted, " << s["loop_closures"]
              << " loop closures; gateway classifier: " << loaded.classifier_note << "\n"
              << "RG map: " << s["regions"] << " regions (" << s["merged_regions"] << " merged away), " << s["gateways"]
              << " gateways (" << s["doors"] << " doors, " << s["neutralized"] << " neutralized), " << s["segments"]
              << " segments, compression " << s["compression"] << ", " << s["consistency_problems"] << " consistency problems\n"
              << "processing: " << run.cpu_seconds << " s CPU for " << run.log_seconds << " s of log\n"
              << "wrote " << out << "/{trajectory.txt,aligned_scans.lcmlog,map.png,rgmap.json,summary.json"
              << (oo.pictures ? ",rgmap.svg,rgmap.png,rgmap_global.pgm,rgmap_global.yaml" : "") << "}\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_rgmap_offline: " << e.what() << "\n";
    return 1;
  }
}
