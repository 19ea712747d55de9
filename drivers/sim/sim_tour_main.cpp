// sim_tour: plans a collision-free closed tour through a world that enters every reachable
// labelled region, and writes it as YAML (stdout, or --out FILE).
#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>

#include "config/config.h"
#include "sim/sim_options.h"
#include "sim/tour_planner.h"
#include "sim/world_yaml.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  CLI::App app{"plan a tour through an rgnav world"};
  std::string world_arg, out_path, sim_config, robot_path, worlds_dir;
  sim::TourOptions options;
  app.add_option("world", world_arg, "world name (under --worlds-dir) or world file")->required();
  app.add_option("--out", out_path, "write the tour here instead of stdout");
  app.add_option("--sim-config", sim_config, "take the robot size from this sim.yaml and its robot description");
  app.add_option("--robot", robot_path, "robot description (default: robot.yaml beside --sim-config)");
  app.add_option("--worlds-dir", worlds_dir, "where world names are looked up");
  app.add_option("--margin", options.margin, "clearance kept beyond the robot radius [m]");
  CLI11_PARSE(app, argc, argv);
  try {
    sim::RobotOptions robot;
    if (!sim_config.empty()) {
      if (robot_path.empty()) robot_path = config::robot_path_beside(sim_config, "robot.yaml");
      robot = sim::load_simulator_options(config::Config::load(sim_config), config::load_robot_description_file(robot_path)).robot;
    }
    const std::string path = sim::resolve_world_path(world_arg, worlds_dir);
    const sim::World world = sim::load_world(path);
    const sim::Tour tour = sim::plan_tour(world, robot, options);
    const std::string yaml = sim::tour_to_yaml(world, tour);
    if (out_path.empty()) {
      std::cout << yaml;
    } else {
      std::ofstream out(out_path);
      if (!(out << yaml)) throw std::runtime_error(out_path + ": cannot write");
    }
    std::cerr << world.name << ": tour of " << tour.waypoints.size() << " waypoints, " << tour.length << " m, visits "
              << tour.visited.size() << " regions";
    if (!tour.unreachable.empty()) std::cerr << ", " << tour.unreachable.size() << " unreachable";
    std::cerr << (tour.collision_free ? "" : " -- NOT collision-free") << "\n";
    return tour.collision_free ? 0 : 1;
  } catch (const config::ConfigError& e) {
    std::cerr << "sim_tour: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "sim_tour: " << e.what() << "\n";
    return 1;
  }
}
