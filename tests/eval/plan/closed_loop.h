// Closed-loop navigation on rgnav's own map of a simulated world, in-process and deterministic:
// the simulated B21r (walking people, ray-cast laser, drifting odometry), collision avoidance,
// the lld follower and rgnav's Planner in lock-step (planned_drive.h).
//   - Goals: random standable points of random regions where the robot's body fits in the true
//     world (table tops, which the laser passes under, count), one after another from where the
//     last one ended. A goal ends reached (the planner says REACHED and the robot is within
//     reached_truth_m of the goal's true position) or at its timeout (timeout_factor x the longer
//     of the reference and the planner's first route, at the planner's speed, + timeout_extra_s:
//     a detour the RG graph forces costs SPL, not success): NO_PATH if the planner says so
//     then (it keeps a goal it found no path for and plans it again when a closed mark expires),
//     else timed out.
//   - Door cases: a door or narrow-passage gateway of the map closed in the simulated world by a
//     door leaf across it (reopening after door_reopen_s), the robot put down on one side and
//     sent to the room on the other: with another way round (through the map's other gateways,
//     and free on the whole grid with the door drawn in) the robot should take it before the
//     door reopens, without NO_PATH; without, the planner should say NO_PATH while the door is
//     closed and get through once it has reopened and the closed mark has expired.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "bench_world.h"
#include "occupancy_grid.h"
#include "planned_drive.h"

namespace rgnav::plan_eval {

struct ClosedLoopOptions
{
  int goals = 100;
  int door_cases = 2;
  double position_tolerance = 0.3;   // [m] NavGoal::position_tolerance
  double reached_truth_m = 0.5;      // [m] the robot's true position from the goal's, when REACHED
  double min_goal_distance = 1.0;    // [m] a new goal at least this far from the robot
  double body_margin = 0.1;          // [m] a goal where the true world leaves the body less room than radius + this is skipped
  double timeout_factor = 3.0;
  double timeout_extra_s = 60.0;     // [s]
  double door_reopen_s = 90.0;       // [s] after the door case's start (the planner waits closed_after_s before NO_PATH)
  double door_case_limit_s = 420.0;  // [s]
  bool trace = false;                // a line per second and per goal to stderr
};

// Pooled over worlds.
struct ClosedLoopSamples
{
  int goals = 0, successes = 0, no_path = 0, timeouts = 0, reached_elsewhere = 0, without_reference = 0;
  int goals_out_of_reach = 0;         // candidate goals skipped: the body does not fit there in the true world
  int goals_with_no_path_report = 0;  // goals the planner said NO_PATH for at some time
  int64_t collisions = 0, replans = 0;
  std::vector<double> spl;            // per goal with a reference path
  std::vector<double> time_s, time_ratio, driven_ratio;   // successful goals: time, time / (shortest / max speed), driven / shortest
  double sim_s = 0, planner_cpu_s = 0;
  int door_cases = 0, door_cases_as_expected = 0;
  int64_t door_collisions = 0;
  std::vector<std::string> contacts;   // what the robot hit in the goal drives (simulator names)

  void add(const ClosedLoopSamples& o);
  nlohmann::json summary() const;
};

// Drives the goals and the door cases in world `w` (its map, truth frames and world with
// people); `space` is the whole grid of w.map (reference lengths for SPL and timeouts).
nlohmann::json run_closed_loop(const localize_eval::BenchWorld& w, const ConfigSpace& space, const ClosedLoopSetup& setup,
                               const ClosedLoopOptions& options, std::mt19937_64& rng, ClosedLoopSamples* totals);

}  // namespace rgnav::plan_eval
