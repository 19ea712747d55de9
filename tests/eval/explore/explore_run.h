// One exploration run of the explorer benchmark, in-process, lock-step and deterministic with a
// seed: the simulated B21r (walking people, ray-cast laser, drifting odometry) with collision
// avoidance and the lld follower (plan_eval::DriveLoop); its scans and odometry go into the RG
// mapping pipeline (scan mapper, gateway detector, RG kernel: RgMapPipeline) as the live
// processes get them; an ExploreDriver turns the pipeline's output (the SLAM pose: the scan
// mapper's estimate for the newest accepted scan composed with odometry since; the RG map;
// the gateway hypotheses) into targets for collision avoidance: rgnav's explorer and planner
// (rg_explore_driver.h), or the frontier baseline (frontier_explorer.h). Measured against the
// true world: rooms entered, free area seen, driven length, collisions, and the explored RG
// map's segmentation as ./rgnav bench rgmap scores it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "ground_truth.h"
#include "lld/lld_options.h"
#include "pipeline_options.h"
#include "rgmap_pipeline.h"
#include "sim/simulator.h"
#include "world_coverage.h"

namespace rgnav::explore_eval {

// The true world, once per world.
struct WorldTruth
{
  std::string name;
  sim::World world;                        // with the people the runs meet
  rgmap_pipeline::GroundTruth truth;       // rooms on `raster`
  Raster raster;
  std::vector<float> clearance;            // per raster cell, searched to clearance_search
  static constexpr double kClearanceSearch = 1.0;   // [m]
};

WorldTruth world_truth(const std::string& name, sim::World world, const sim::RobotOptions& robot);

// One start of a world: what is reachable from it.
struct StartTruth
{
  std::string label;                       // "fixed", "random1", ...
  sim::Pose2 start;
  ReachableArea area;
  std::vector<std::string> reachable_rooms;   // the ground-truth tour's rooms from this start
  std::vector<std::string> unreachable_rooms;
  double tour_length_m = 0;                // the ground-truth tour from this start (closed: back to the start)
};

StartTruth start_truth(const WorldTruth& w, const sim::Pose2& start, const std::string& label, const sim::RobotOptions& robot);

struct RunSetup
{
  const rgmap_pipeline::LoadedPipeline& pipeline;
  const lld::LldOptions& lld;
  const collision_avoidance::CaOptions& ca;
  sim::SimulatorOptions sim;
  double max_sim_s = 3600.0;               // cap (a timeout)
  double seen_range_m = 8.0;               // [m] beams count as seeing up to here (the RG kernel's freespace range)
  double gateway_match_m = 1.0;            // rgmap bench's default
  // > 0: the robot first turns on the spot this long at 0.5 rad/s before the driver takes over
  // (a look around: the laser sees only ahead). 0: the driver starts at once.
  double spin_at_start_s = 0.0;
  // Collision avoidance hears what the vision would see of solids the laser misses (from ground
  // truth: vision_stand_in.h); false: the laser alone.
  bool vision = true;
  bool trace = false;
};

// The pipeline's newest output, for a driver.
struct PipelineView
{
  rgmap_pipeline::RgMapPipeline& pipeline;
  int64_t utime = 0;
  geometry::Pose2 map_from_base;           // the SLAM pose now (map frame)
  geometry::Pose2 odom_from_base;          // odometry now
  bool cannot_pass = false;                // collision avoidance stands without a way (blocked or reactive)
};

// What drives the robot.
class ExploreDriver
{
 public:
  virtual ~ExploreDriver() = default;
  virtual std::string method() const = 0;
  // The pipeline accepted a scan (last_aligned(), last_detection()).
  virtual void on_aligned(rgmap_pipeline::RgMapPipeline& pipeline) = 0;
  // Every period once there are odometry and a SLAM pose: targets for collision avoidance, if new.
  virtual std::optional<collision_avoidance::Targets> step(const PipelineView& view) = 0;
  // The driver says it has explored everything it can.
  virtual bool done() const = 0;
  // One line for EXPLORE_TRACE.
  virtual std::string trace_line() const = 0;
  virtual nlohmann::json stats() const = 0;
};

struct RunResult
{
  std::string method, start;
  bool ended_done = false, timed_out = false, premature = false;
  double sim_s = 0, wall_s = 0, driven_m = 0;
  double time_to_90_s = NAN;               // [s] area seen reached 90 % of the reachable free area
  double area_seen_ratio = 0;
  int rooms_reachable = 0, rooms_entered = 0;
  std::vector<std::string> rooms_missed;
  int64_t collisions = 0;
  std::vector<std::string> contacts;
  double seg_precision = NAN, seg_recall = NAN;
  nlohmann::json detail;
};

// Runs `driver` from `start` until it is done or max_sim_s; `map_dir` (non-empty) gets the
// explored RG map's outputs (rgmap.png, ...).
RunResult run_exploration(const WorldTruth& w, const StartTruth& start, ExploreDriver& driver, const RunSetup& setup,
                          uint64_t seed, const std::string& map_dir);

nlohmann::json to_json(const RunResult& r);

}  // namespace rgnav::explore_eval
