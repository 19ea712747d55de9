#include "bench_world.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "bench_stats.h"
#include "offline_run.h"
#include "render/rgmap_picture.h"
#include "sim/tour_planner.h"
#include "sim/world_yaml.h"
#include "sim_rgmap.h"

namespace rgnav::localize_eval {

namespace rp = rgmap_pipeline;
using geometry::Pose2;

void add_walkers(sim::World* world, const std::vector<sim::Vec2>& tour, int count)
{
  if (!world->people.empty() || tour.size() < 4) return;
  for (int i = 0; i < count; ++i) {
    sim::Person p;
    p.name = "bench_walker_" + std::to_string(i);
    const size_t a = tour.size() * static_cast<size_t>(i + 1) / static_cast<size_t>(count + 1);
    for (size_t k = a; k < std::min(tour.size(), a + 6); ++k) p.path.push_back(tour[k]);
    std::reverse(p.path.begin(), p.path.end());
    p.loop = false;
    p.speed = 0.6 + 0.1 * i;
    world->people.push_back(p);
  }
}

BenchWorld map_world(const std::string& name, const std::string& path, const std::string& out_dir,
                     const sim::SimulatorOptions& sim_options, const rp::LoadedPipeline& loaded,
                     const Pose2& base_from_laser, int walkers)
{
  BenchWorld w;
  w.name = name;
  w.dir = out_dir + "/" + name;
  w.world = sim::load_world(path);
  w.tour = sim::plan_tour(w.world, sim_options.robot).waypoints;
  // The map: one lap of the tour, mapped by scan mapper + gateway detector + RG kernel.
  rp::SimTourOptions mapping;
  mapping.laps = 1;
  mapping.max_sim_s = 2400;
  const auto run = rp::run_sim_rgmap(w.world, sim_options, loaded, mapping);
  rp::write_run_outputs(run.run, loaded.options, w.dir);
  w.map = run.run.map;
  w.frames = fit_truth_frames(run.run, run.truth_at_node, base_from_laser);
  w.frames.map = &w.map;
  w.grid_from_region = render::compose_region_frames(w.map);
  // A fresh folder: MRPT's runner takes every drive folder it finds there.
  std::filesystem::remove_all(w.dir + "/mrpt");
  std::filesystem::create_directories(w.dir + "/mrpt");
  render::write_map_server(render::compose_global_grid(w.map, 0.05), w.dir + "/mrpt/map");
  add_walkers(&w.world, w.tour, walkers);
  return w;
}

nlohmann::json map_quality(const BenchWorld& w)
{
  nlohmann::json j;
  j["regions"] = static_cast<int>(w.frames.world_from_region.size());
  std::vector<double> fit;
  for (const auto& [id, e] : w.frames.fit_rmse) fit.push_back(e);
  j["region_fit_rmse_m_p50"] = number_or_null(percentile(fit, 0.5));
  j["region_fit_rmse_m_max"] = number_or_null(fit.empty() ? NAN : *std::max_element(fit.begin(), fit.end()));
  std::vector<double> link_errors;
  for (const auto& [id, g] : w.map.gateways()) {
    const int64_t a = w.map.resolve(g.region_a), b = g.region_b ? w.map.resolve(g.region_b) : 0;
    if (b == 0 || a == b || g.neutralized || !w.frames.world_from_region.count(a) || !w.frames.world_from_region.count(b) ||
        g.crossing_points.empty())
      continue;
    const Pose2 truth_ab = w.frames.world_from_region.at(a).inverse() * w.frames.world_from_region.at(b);
    const Eigen::Vector2d at_a = g.crossing_points.front();
    const Eigen::Vector2d via_link = g.region_a_from_region_b * (truth_ab.inverse() * at_a);
    link_errors.push_back((via_link - at_a).norm());
    if (std::getenv("LOCALIZE_TRACE"))
      std::cerr << w.name << " gateway " << id << " regions " << a << "-" << b << " link error " << link_errors.back() << " m\n";
  }
  j["gateway_link_error_m_p50"] = number_or_null(percentile(link_errors, 0.5));
  j["gateway_link_error_m_max"] = number_or_null(link_errors.empty() ? NAN : *std::max_element(link_errors.begin(), link_errors.end()));
  return j;
}

std::pair<size_t, double> random_tour_point(const std::vector<sim::Vec2>& tour, std::mt19937_64& rng)
{
  std::vector<double> lengths;
  for (size_t k = 0; k + 1 < tour.size(); ++k) lengths.push_back((tour[k + 1] - tour[k]).norm());
  std::discrete_distribution<size_t> pick(lengths.begin(), lengths.end());
  return {pick(rng), std::uniform_real_distribution<double>(0.0, 1.0)(rng)};
}

}  // namespace rgnav::localize_eval
