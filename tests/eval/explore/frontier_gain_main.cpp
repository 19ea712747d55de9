// rgnav_frontier_gain: every live region's frontiers in a saved RG map (rgmap.json, as the
// explore bench and the demo write it) with what a look past each can still show (the explorer's
// view gain, procs/explorer/view_gain.h) and whether the explorer takes it for a goal: to see
// why a region counts as complete, or why the explorer still drives to one.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>
#include <optional>

#include "config/config.h"
#include "config/robot_description.h"
#include "explorer/explorer_options.h"
#include "explorer/frontiers.h"
#include "explorer/view_gain.h"
#include "rgmap/rgmap_json.h"

using namespace rgnav;

int main(int argc, char** argv)
{
  CLI::App app{"frontiers of a saved RG map and the unknown area past each"};
  std::string map_path, explorer_config = "config/explorer.yaml", robot = "config/robot.yaml";
  app.add_option("map", map_path, "rgmap.json")->required()->check(CLI::ExistingFile);
  app.add_option("--explorer-config", explorer_config, "explorer config (frontier section)")->check(CLI::ExistingFile);
  app.add_option("--robot", robot, "robot description")->check(CLI::ExistingFile);
  std::optional<double> min_gain;
  app.add_option("--min-gain", min_gain, "[m^2] the rule's threshold (default: the config's frontier.min_gain_m2)")
      ->check(CLI::Range(0.0, 100.0));
  CLI11_PARSE(app, argc, argv);
  try {
    auto options =
        explorer::load_explorer_options(config::Config::load(explorer_config), config::load_robot_description_file(robot));
    if (min_gain) options.frontier.gain.min_m2 = *min_gain;
    nlohmann::json j;
    std::ifstream(map_path) >> j;
    const rgmap::RgMap map = rgmap::from_json(j);
    int goals = 0, closed = 0;
    for (const auto& [id, r] : map.regions()) {
      if (r.state == rgmap::Region::State::kMerged) continue;
      const auto found = explorer::find_frontiers(map, id, options.frontier);
      for (const auto& f : found.frontiers) {
        const Eigen::Vector2d at = r.map_from_region * f.goal, out = r.map_from_region.rotation() * f.outward;
        const double gain = explorer::unknown_area_beyond(map, at, out, options.frontier.gain);
        const bool goal = gain >= options.frontier.gain.min_m2;
        (goal ? goals : closed) += 1;
        std::cout << fmt::format("region {:3d} state {} frontier at ({:6.2f}, {:6.2f}) outward ({:5.2f}, {:5.2f}) width {:4.2f} m "
                                 "unknown beyond {:4.2f} m^2 {}\n",
                                 id, static_cast<int>(r.state), at.x(), at.y(), out.x(), out.y(), f.width, gain,
                                 goal ? "goal" : "nothing to see");
      }
    }
    std::cout << fmt::format("{} frontiers: {} goals, {} with less than {:.2f} m^2 unknown beyond\n", goals + closed, goals,
                             closed, options.frontier.gain.min_m2);
  } catch (const std::exception& e) {
    std::cerr << "rgnav_frontier_gain: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
