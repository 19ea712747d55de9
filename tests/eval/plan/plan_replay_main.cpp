// rgnav_plan_replay: plans once more what the planner found no path for, from a dump of the map,
// the robot's pose and the goal (the explore bench's EXPLORE_DUMP_NO_PATH=DIR writes them), and
// says where the route breaks: the start's and the goal's place in their regions' grids, and which
// of the start region's and the goal region's gateway crossings the robot or the goal reaches.
// With --png, each of the two regions' planning grids as a picture (blocked dark, free by cost
// level, start green, goal red, crossings blue).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>
#include <iostream>

#include "config/config.h"
#include "config/robot_description.h"
#include "planner/global_planner.h"
#include "planner/planner_options.h"
#include "rgmap/rg_graph.h"
#include "rgmap/rgmap_json.h"

using namespace rgnav;

namespace {

geometry::Pose2 pose_of(const nlohmann::json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

void draw(const planner::RegionGrid& grid, const std::vector<std::pair<Eigen::Vector2d, cv::Scalar>>& marks,
          const std::string& path)
{
  cv::Mat img(grid.height(), grid.width(), CV_8UC3);
  for (int y = 0; y < grid.height(); ++y)
    for (int x = 0; x < grid.width(); ++x) {
      const planner::Cell c{x, y};
      const uint8_t v = grid.free(c) ? static_cast<uint8_t>(255 - 30 * grid.level(c)) : 40;
      img.at<cv::Vec3b>(grid.height() - 1 - y, x) = {v, v, v};
    }
  for (const auto& [p, colour] : marks) {
    const auto c = grid.cell_of(p);
    cv::circle(img, {c.x(), grid.height() - 1 - c.y()}, 3, colour, -1);
  }
  cv::Mat big;
  cv::resize(img, big, {}, 4, 4, cv::INTER_NEAREST);
  cv::imwrite(path, big);
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Plan again what the planner found no path for, from a dump, and say where the route breaks"};
  std::string dump, config_path = "config/planner.yaml", robot_path = "config/robot.yaml", png;
  app.add_option("dump", dump, "no_path_<n>.json")->required()->check(CLI::ExistingFile);
  app.add_option("--config", config_path, "planner config")->check(CLI::ExistingFile);
  app.add_option("--robot", robot_path, "robot description")->check(CLI::ExistingFile);
  app.add_option("--png", png, "picture prefix: <prefix>_start.png, <prefix>_goal.png");
  CLI11_PARSE(app, argc, argv);

  nlohmann::json j;
  std::ifstream(dump) >> j;
  const auto cfg = config::Config::load(config_path);
  const auto options = planner::load_planner_options(cfg, config::load_robot_description_file(robot_path));
  const rgmap::RgMap map = rgmap::from_json(j.at("map"));
  planner::GlobalPlanner planner(options);
  planner.set_map(map);

  planner::PlanRequest req;
  req.start_region = j["pose"]["region"].get<int64_t>();
  req.start = pose_of(j["pose"]["region_from_base"]).translation();
  req.goal_region = j["goal"]["region"].get<int64_t>();
  req.goal = pose_of(j["goal"]["region_from_goal"]).translation();
  if (j["goal"]["beyond_known"].get<bool>()) req.goal_reach = options.grid.beyond_known_reach;
  req.now_s = 0;
  std::cout << "dumped reason: " << j["reason"].get<std::string>() << "\n";
  std::string why;
  const auto route = planner.plan(req, &why);
  std::cout << "replanned: " << (route ? "a route" : "no path: " + why) << "\n";

  auto report = [&](int64_t region, const Eigen::Vector2d& p, const std::string& what, double reach) {
    const auto* rp = planner.region_planner(region);
    if (!rp) { std::cout << what << ": region " << region << " unknown\n"; return; }
    const auto c = rp->grid().cell_of(p);
    std::cout << what << " region " << region << " (" << p.transpose() << "): cell free " << rp->grid().free(c)
              << " component " << rp->grid().component(c) << " (main " << rp->grid().main_component() << ") standable "
              << rp->standable(p, reach) << " cut off " << rp->cut_off(p, reach) << "\n";
    std::vector<std::pair<Eigen::Vector2d, cv::Scalar>> marks{{p, what == "start" ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 255)}};
    if (what == "goal" && j["goal"].contains("looked_at_map")) {
      // The stack entry's crossing or the frontier the goal is for (yellow).
      const auto& m = j["goal"]["looked_at_map"];
      const Eigen::Vector2d at = map.region(region)->map_from_region.inverse() * Eigen::Vector2d(m[0].get<double>(), m[1].get<double>());
      std::cout << "  for a " << j["goal"].value("kind", "goal") << " at (" << at.transpose() << ")\n";
      marks.push_back({at, cv::Scalar(0, 220, 220)});
    }
    // The crossing points the planner's search joins the start and the goal to (rgmap::build_graph's
    // nodes), with the reaches GlobalPlanner::region_path gives them.
    const auto graph = rgmap::build_graph(map);
    for (const auto& n : graph.nodes) {
      if (map.resolve(n.region_id) != map.resolve(region)) continue;
      std::string path_why;
      const double crossing_reach = options.global.crossing_reach;
      const double own_reach = reach > 0 ? reach : options.grid.adapt_distance;
      const auto path = what == "start" ? rp->plan(p, n.point, &path_why, own_reach, crossing_reach, false, true)
                                        : rp->plan(n.point, p, &path_why, crossing_reach, own_reach, reach > 0);
      const auto* g = map.gateway(n.gateway_id);
      std::cout << "  node " << n.id << " gateway " << n.gateway_id << " (" << (g ? rgmap::to_string(g->cls) : "?") << ", "
                << (g ? g->region_a : 0) << "-" << (g ? g->region_b : 0) << ") at (" << n.point.transpose() << "): "
                << (path ? "path " + std::to_string(path->cost) : "none: " + path_why) << "\n";
      marks.push_back({n.point, cv::Scalar(255, 0, 0)});
    }
    if (!png.empty()) draw(rp->grid(), marks, png + "_" + what + ".png");
  };
  report(req.start_region, req.start, "start", -1);
  report(req.goal_region, req.goal, "goal", req.goal_reach);
  return route ? 0 : 1;
}
