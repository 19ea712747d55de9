// A whole tour through a simulated building for control_bench and the tests: the simulated
// B21r (walking people, ray-cast LMS 2xx, drifting odometry), collision avoidance and the lld
// follower in lock-step, fed the way the demo feeds them. The tour runner's sequencer hands
// on the next targets when one is reached and re-sends them every 0.5 s (as tour_runner does
// on its 2 Hz cadence, with the goal id it publishes); a perfect localizer re-expresses them
// in the odometry frame. What it measures is whether the robot gets through the building's
// doors and halls past the people, and how long it stood without reaching a target.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "lld/follower.h"
#include "lld/lld_options.h"
#include "sim/simulator.h"
#include "sim/world.h"

namespace rgnav::bench {

struct TourRunOptions
{
  uint64_t seed = 1;              // odometry and laser noise
  double people_delay_s = 0.0;    // added to every person's start delay (shifts where they meet the robot)
  double time_limit_s = 1500.0;   // [s] simulated
  double resend_period_s = 0.5;   // [s] tour_runner's cadence
  double max_spacing_m = 1.5;     // tour_runner's densify spacing
  double reach_radius_m = 0.35;   // tour_runner's sequencer
  double max_speed = 0.6;         // [m/s]
  bool trace = false;             // one line per second to stderr
};

struct TourRunResult
{
  size_t targets = 0;
  size_t reached = 0;
  double time_s = 0.0;              // simulated time at the end (tour done or time limit)
  double longest_stall_s = 0.0;     // longest time between two targets reached
  Eigen::Vector2d stall_at{0, 0};   // world position where that stall began
  size_t stall_target = 0;          // index (1-based) of the target it waited for
  int64_t collisions = 0;
  int64_t fallbacks = 0;
  bool completed() const { return reached == targets; }
};

// The simulator as control_bench runs it: its odometry error (systematic and random; the
// targets must follow that drift through the localizer), the laser on or off.
sim::SimulatorOptions control_sim_options(uint64_t seed, bool laser);

// Hands one simulator step's odometry and scans to collision avoidance, as its node does;
// `odometry` becomes the newest odometry sample. Returns whether there was one.
bool feed_collision_avoidance(const sim::StepOutput& out, collision_avoidance::CollisionAvoidance& ca,
                              lld::OdometryInput* odometry);

// Hands collision avoidance the follower's status, and the follower collision avoidance's
// trajectory, as their nodes do over the bus: a new one (an id other than *last_id) replaces the
// follower's plan, starting at its last commanded speed; the same one refreshes it.
void hand_over_trajectory(collision_avoidance::CollisionAvoidance& ca, lld::Follower& follower,
                          const lld::FollowerOptions& options, time::Time now, int64_t* last_id);

// The world's tour as the demo has it: the world's own, or the one `rgnav demo` plans
// (sim_tour with --margin 0.15, deploy/cli/demo.sh). Empty: no tour through the world.
std::vector<Eigen::Vector2d> demo_tour(const sim::World& world);

// Drives `world_points` (world frame, the tour's waypoints; densified like tour_runner) from
// the world's start pose.
TourRunResult run_tour(const sim::World& world, const std::vector<Eigen::Vector2d>& world_points,
                       const lld::LldOptions& lld_options, const collision_avoidance::CaOptions& ca_options,
                       const TourRunOptions& options);

}  // namespace rgnav::bench
