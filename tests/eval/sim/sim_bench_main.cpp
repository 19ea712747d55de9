// sim_bench: measures the ray caster (scans of 181 beams per second in the office world,
// one core) and the whole simulator in lock-step at 75 Hz (simulated seconds per wall
// second while driving the office tour). Writes JSON for deploy/bench/sim.sh.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <iostream>

#include "sim/tour_planner.h"
#include "sim/waypoint_follower.h"
#include "sim/world_yaml.h"

int main(int argc, char** argv)
{
  using namespace rgnav::sim;
  using Clock = std::chrono::steady_clock;
  CLI::App app{"simulator benchmark"};
  std::string world_path, out_path;
  double seconds = 3.0;
  app.add_option("--world", world_path, "office world file")->required();
  app.add_option("--out", out_path, "JSON output");
  app.add_option("--seconds", seconds, "wall time per measurement");
  CLI11_PARSE(app, argc, argv);

  const World world = load_world(world_path);
  SimulatorOptions options;
  options.seed = 7;
  const Tour tour = plan_tour(world, options.robot);

  // 1. Ray casting: scans from poses along the tour (realistic positions, all headings).
  const Scene scene(world);
  Lms2xxModel laser(options.laser, Rng(1));
  std::vector<uint8_t> doors(world.doors.size(), 1);
  std::vector<Pose2> poses;
  for (size_t k = 0; k + 1 < tour.waypoints.size(); ++k)
    for (int s = 0; s < 10; ++s) {
      const Vec2 p = tour.waypoints[k] + (tour.waypoints[k + 1] - tour.waypoints[k]) * (s / 10.0);
      poses.push_back({p.x(), p.y(), 0.37 * static_cast<double>(poses.size())});
    }
  int64_t scans = 0;
  double checksum = 0.0;
  const auto t0 = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - t0).count() < seconds) {
    for (int i = 0; i < 100; ++i) {
      const auto r = laser.true_ranges(scene, doors, {}, poses[static_cast<size_t>(scans) % poses.size()]);
      checksum += r[90] < 1e9 ? r[90] : 0.0;
      ++scans;
    }
  }
  const double ray_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const double scans_per_s = scans / ray_s;

  // 2. The whole simulator in lock-step, 75 Hz scans, 50 Hz odometry, 1 kHz physics, people.
  Simulator sim(world, options);
  WaypointFollower follower(tour.waypoints, [&sim] { return sim.truth(); });
  sim.set_command_source(&follower);
  const auto t1 = Clock::now();
  int64_t sim_scans = 0;
  while (std::chrono::duration<double>(Clock::now() - t1).count() < seconds) {
    const auto out = sim.step(std::chrono::microseconds(13333));
    sim_scans += static_cast<int64_t>(out.scans.size());
  }
  const double wall = std::chrono::duration<double>(Clock::now() - t1).count();
  const double factor = sim.time_s() / wall;

  nlohmann::json j;
  j["raycast_scans_per_s"] = scans_per_s;
  j["raycast_beams"] = options.laser.beams;
  j["realtime_factor_lockstep"] = factor;
  j["lockstep_simulated_s"] = sim.time_s();
  j["lockstep_scans"] = sim_scans;
  j["lockstep_collisions"] = sim.collisions();
  j["world"] = world.name;
  j["world_walls"] = world.walls.size();
  j["scene_segments"] = scene.segments().size();
  j["checksum"] = checksum;
  const std::string text = j.dump(2);
  std::cout << text << "\n";
  if (!out_path.empty()) std::ofstream(out_path) << text << "\n";
  return 0;
}
