// The RG mapping pipeline on the simulated B21r with exact ground truth: the lock-step simulator
// drives a closed tour that enters every reachable labelled room of a world, as fast as the CPU
// allows; its scans and odometry go straight into the pipeline (no LCM). The resulting RG map is
// placed in the world by the rigid fit of its accepted scans' estimates to their true poses and
// scored against the world's rooms, gateways and room graph (rgmap_metrics.h, ground_truth.h).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "ghost_segments.h"
#include "ground_truth.h"
#include "offline_run.h"
#include "segmentation_diagnosis.h"
#include "sim/simulator.h"

namespace rgnav::rgmap_pipeline {

struct SimTourOptions
{
  int laps = 1;
  double max_sim_s = 1800.0;   // cap on simulated time (a benchmark must end)
  // The world's walking people: left out unless asked for (they are no part of the ground truth).
  // Kept, they are seen by the laser but neither they nor the robot make way and the robot's body
  // passes through them (SimulatorOptions::people_block_robot): the tour follower has no obstacle
  // avoidance, and a person in its way would stop the tour for good. The tour is then the same
  // as without them: what they change is what the map makes of them.
  bool people = false;
  // The scans go to the RG kernel at the simulator's true poses (the scan mapper is not used):
  // separates segmentation errors from SLAM errors. Not the headline: the robot has no true poses.
  bool true_poses = false;
};

struct SimRgMapRun
{
  std::string world;
  std::vector<std::string> visited;    // rooms the planned tour enters
  std::vector<std::string> unreachable;
  double tour_length_m = 0;
  bool capped = false;
  double sim_seconds = 0, driven_m = 0, sim_cpu_seconds = 0;
  int64_t collisions = 0;
  OfflineRun run;
  std::vector<geometry::Pose2> truth_at_node;   // true pose of every accepted scan (run.nodes)
  std::vector<Eigen::Vector2d> true_path;       // true positions, every 5 cm
};

// A simulated scan as the mapper would get it from LASER_FRONT: header rounded to float, ids
// from 1.
sensors::LaserScan as_laser_front(const sensors::LaserScan& simulated);

// The laser mounting pose of `loaded` is replaced by the simulated robot's.
SimRgMapRun run_sim_rgmap(sim::World world, const sim::SimulatorOptions& sim_options, LoadedPipeline loaded,
                          const SimTourOptions& options);

struct WorldScore
{
  geometry::Pose2 world_from_map;
  double alignment_rmse_m = 0;     // of the accepted scans after the rigid fit
  SegmentationScore segmentation;
  SegmentationDiagnosis segmentation_diagnosis;   // where the precision is lost
  GatewayMatch gateways;            // against every gateway between explored rooms
  std::vector<Eigen::Vector2d> gateway_truth_positions;   // world frame, indices of gateways.pairs' first
  std::vector<Eigen::Vector2d> gateway_found_positions;   // world frame, indices of gateways.pairs' second
  GatewayMatch gateways_crossed;    // against the gateways the robot went through
  GraphComparison graph;            // against the room graph of the explored rooms
  MapCounts counts;
  GhostSegments ghosts;             // line-map segments with nothing static of the world behind them
};

// statics: the world's static surfaces for the ghost-segment count (left at 0 without).
WorldScore score_world(const SimRgMapRun& run, const GroundTruth& truth, double gateway_match_distance,
                       const StaticSurfaces* statics = nullptr);

nlohmann::json to_json(const SimRgMapRun& run, const WorldScore& score);

}  // namespace rgnav::rgmap_pipeline
