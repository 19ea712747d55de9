// The scan mapper on the simulated B21r with exact ground truth: the lock-step simulator
// (drivers/sim) drives a closed tour through a world, as fast as the CPU allows, and its
// scans and odometry go straight into the mapping library (no LCM). The estimate of every
// accepted scan is compared with the simulator's true pose by the relations metric of
// Kuemmerle et al. 2009 (consecutive accepted scans, plus all pairs closer than 1 m and more
// than 30 s apart) and the absolute trajectory error.
#pragma once

#include <string>

#include "scan_mapper/relations_metric.h"
#include "scan_mapper/scan_mapper.h"
#include "sim/simulator.h"

namespace rgnav::scan_mapper {

struct SimMappingOptions
{
  int laps = 2;                 // the planned tour is driven this often (more loops)
  double max_sim_s = 1800.0;    // cap on simulated time per world (a benchmark must end)
  // Keep the world's people walking: the laser sees them, the robot's body passes through
  // them (SimulatorOptions::people_block_robot), so the tour is the same as without them.
  bool keep_people = false;
};

struct SimMappingResult
{
  std::string world;
  double tour_length_m = 0.0;   // planned tour, one lap
  int laps = 0;
  bool capped = false;          // stopped at max_sim_s before the tour was done
  int people_removed = 0;       // people of the world left out (static building only)
  int people_walking = 0;       // people kept walking (keep_people)
  double driven_m = 0.0;        // true path length driven
  double sim_seconds = 0.0;     // simulated time
  double mapping_cpu_seconds = 0.0;  // CPU time inside the mapping library (this thread)
  double sim_cpu_seconds = 0.0;      // CPU time of the simulator (ray casting, physics)
  int64_t collisions = 0;
  MapperStats stats;
  RelationError relations;
  double ate_rmse_m = 0.0;
  double odometry_ate_rmse_m = 0.0;  // raw odometry at the same scans, for comparison
  // Loop-closure edges of the final graph whose measured relative pose is more than 0.1 m off
  // the true one (false closures: a look-alike place, a hallway's doors at regular spacing).
  int loop_closures_wrong = 0;
  // Those of them whose error at the true poses, weighed by the edge's own information, is
  // above loop.max_residual_chi2 (a hallway closure off along the axis costs little).
  int loop_closures_inconsistent = 0;
  // Every loop-closure edge of the final graph against the truth (closures.txt of the bench).
  struct ClosureCheck
  {
    int64_t from = 0, to = 0;
    Eigen::Vector3d error_at_truth = Eigen::Vector3d::Zero();   // edge_error at the true poses
    double chi2_at_truth = 0.0;                                 // weighed by the edge's information
    double sigma_max_m = 0.0;                                   // along its weakest direction
  };
  std::vector<ClosureCheck> closures;
  std::vector<ScanNode> nodes;
  std::vector<Pose2> truth;          // true pose at each node's scan
  std::vector<Pose2> online;         // each node's estimate when it was added (before later closures)
  std::vector<int> loop_closed_at;   // nodes whose scan closed a loop
};

SimMappingResult run_sim_mapping(const std::string& world_path, const sim::SimulatorOptions& sim_options,
                                 ScanMapperOptions mapper_options, const SimMappingOptions& options);

}  // namespace rgnav::scan_mapper
