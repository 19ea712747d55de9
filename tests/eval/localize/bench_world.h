// One world of the localization benchmark: its map built by rgnav's pipeline (one lap of the
// world's tour), each region placed in the world (truth_frames.h), the occupancy grid MRPT gets,
// and walkers for a world without people.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "geometry/pose2.h"
#include "pipeline_options.h"
#include "rgmap/rg_map.h"
#include "sim/simulator.h"
#include "truth_frames.h"

namespace rgnav::localize_eval {

struct BenchWorld
{
  std::string name, dir;
  sim::World world;
  std::vector<sim::Vec2> tour;
  rgmap::RgMap map;
  TruthFrames frames;
  std::map<int64_t, geometry::Pose2> grid_from_region;   // the frames of MRPT's occupancy grid

  // The true pose in the grid's frame, through region `region`.
  geometry::Pose2 truth_in_grid(int64_t region, const geometry::Pose2& truth) const
  {
    return grid_from_region.at(region) * frames.in_region(region, truth);
  }
};

// Maps the world (outputs under out_dir/name, MRPT's grid under out_dir/name/mrpt/map.*) and adds
// `walkers` people pacing stretches of the tour if the world has none.
BenchWorld map_world(const std::string& name, const std::string& path, const std::string& out_dir,
                     const sim::SimulatorOptions& sim_options, const rgmap_pipeline::LoadedPipeline& loaded,
                     const geometry::Pose2& base_from_laser, int walkers);

// Walkers for a world that has none: `count` people pacing stretches of the robot's own tour
// (they meet it head on in hallways and doors, the hard case for scan matching).
void add_walkers(sim::World* world, const std::vector<sim::Vec2>& tour, int count);

// How good the map itself is: the per-region fits, and how far each gateway's transform between
// its regions is from their true placement at the gateway (the map's own inconsistency, which
// no localizer can undo at a hand-over). LOCALIZE_TRACE prints every gateway's.
nlohmann::json map_quality(const BenchWorld& w);

// A random point along the tour (segment k, fraction s), segments weighted by length.
std::pair<size_t, double> random_tour_point(const std::vector<sim::Vec2>& tour, std::mt19937_64& rng);

}  // namespace rgnav::localize_eval
