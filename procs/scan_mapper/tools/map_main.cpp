// rgnav_map: the scan mapper offline over an LCM log (LASER_FRONT + ODOMETRY).
//   rgnav_map LOG.lcmlog --out DIR [--config config/scan_mapper.yaml] [--robot config/robot.yaml]
//             [--base-from-laser X Y THETA]
// Writes DIR/trajectory.txt, DIR/aligned_scans.lcmlog, DIR/map.png and prints a summary.
#include <CLI/CLI.hpp>

#include <iostream>

#include "importers/log_to_map.h"
#include "offline_mapping.h"
#include "offline_options.h"
#include "runtime/process_main.h"
#include "scan_mapper/scan_mapper_options.h"

namespace sm = rgnav::scan_mapper;

int main(int argc, char** argv)
{
  CLI::App app{"Map an LCM log offline with the scan mapper"};
  std::string log_path, out, config_path = rgnav::runtime::default_config_dir() + "/scan_mapper.yaml", robot_path;
  std::vector<double> mount;
  app.add_option("log", log_path, "LCM log with LASER_FRONT and ODOMETRY")->required()->check(CLI::ExistingFile);
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--config", config_path, "scan mapper config");
  app.add_option("--robot", robot_path, "robot description (default: robot.yaml beside the config)");
  app.add_option("--base-from-laser", mount, "laser mounting pose of the logged robot: x y theta [m m rad]")->expected(3);
  CLI11_PARSE(app, argc, argv);
  sm::ScanMapperOptions options;
  try {
    if (robot_path.empty()) robot_path = rgnav::runtime::default_robot_path(config_path);
    options = sm::load_offline_options(config_path, rgnav::config::load_robot_description_file(robot_path));
  } catch (const std::exception& e) {
    std::cerr << "rgnav_map: " << e.what() << "\n";
    return 2;
  }
  if (mount.size() == 3) options.base_from_laser = sm::Pose2{mount[0], mount[1], sm::normalize_angle(mount[2])};
  try {
    const auto log = rgnav::importers::read_log_to_map(log_path, "rgnav_map");
    if (!log) return 1;
    const auto r = sm::run_offline(*log, options);
    const double consistency = sm::write_outputs(r, options, out);
    const auto& s = r.stats;
    std::cout << log_path << ": " << s.scans_in << " scans, " << s.accepted << " accepted, " << s.matched
              << " matched, " << s.correlative_retries << " correlative retries, " << s.match_rejected
              << " matches rejected, " << s.turns_held << " turns held to odometry's heading, " << s.axes_held
              << " weakest directions left to odometry, " << s.no_odometry
              << " without odometry, " << s.moving_points << " points left out as moving\n"
              << "odometry translation noise: " << s.odometry_trans_scale << " x the configured (learned)\n"
              << "odometry translation scale: " << s.odometry_scale << " (learned: true / odometry)\n"
              << "loop closures: " << s.loop_closures << " of " << s.loop_attempts << " attempts ("
              << s.loop_rejected_after_opt << " removed as inconsistent)\n"
              << "processing: " << r.cpu_seconds << " s CPU (" << r.wall_seconds << " s wall) for " << r.log_seconds
              << " s of log: realtime factor " << (r.cpu_seconds > 0 ? r.log_seconds / r.cpu_seconds : 0.0) << "\n"
              << "map consistency (end points within 5 cm of occupied cells): " << consistency << "\n"
              << "wrote " << out << "/{trajectory.txt,aligned_scans.lcmlog,map.png}\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_map: " << e.what() << "\n";
    return 1;
  }
}
