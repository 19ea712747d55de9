// The simulator, collision avoidance and the lld follower in lock-step at the lld's 20 Hz, as the
// control benchmark's office tour runs them (office_tour.h), split in two halves around whatever
// gives collision avoidance its targets (rgnav's planner in planned_drive.h, the explorer
// benchmark's frontier baseline): sense() steps the simulator and hands its odometry and scans to
// collision avoidance; act() hands collision avoidance's trajectory to the follower and the
// follower's command to the simulated drive.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "lld/follower.h"
#include "lld/lld_options.h"
#include "planner/planner_options.h"
#include "sim/simulator.h"

namespace rgnav::config { struct RobotDescription; }

namespace rgnav::plan_eval {

// The drive chain's options as the benchmarks run it, from its processes' config files, each
// checked for unknown keys (the sections only the processes read left out).
struct DriveChainFiles
{
  std::string sim, planner, lld, ca;
};
struct DriveChainOptions
{
  sim::SimulatorOptions sim;
  planner::PlannerOptions planner;
  lld::LldOptions lld;
  collision_avoidance::CaOptions ca;
};
DriveChainOptions load_drive_chain(const DriveChainFiles& files, const config::RobotDescription& robot);

class DriveLoop
{
 public:
  // The robot starts at world.start.
  DriveLoop(const sim::World& world, const sim::SimulatorOptions& sim_options, const lld::LldOptions& lld,
            const collision_avoidance::CaOptions& ca);
  DriveLoop(const DriveLoop&) = delete;
  DriveLoop& operator=(const DriveLoop&) = delete;

  static constexpr double kPeriod = 0.05;   // [s] the lld's loop
  static constexpr std::chrono::microseconds kPeriodUs{50'000};

  // First half of a period: the simulator's step; its odometry and scans go to collision
  // avoidance, the true pose and what the robot hit are kept. The step's output.
  const sim::StepOutput& sense();
  // Whether odometry has come (before it, act() must not be called).
  bool ready() const { return have_odometry_; }
  void set_targets(const collision_avoidance::Targets& targets) { ca_.set_targets(targets); }
  // OBSTACLES_3D's points (odometry frame), as the node gives them to collision avoidance.
  void obstacle_points(int64_t utime, std::vector<Eigen::Vector2d> odom_points)
  {
    ca_.on_obstacle_points(time::from_utime(utime), std::move(odom_points));
  }
  // Second half: the trajectory to the follower, the follower's command to the drive.
  void act();
  // Instead of act(): the drive told these velocities directly for this period.
  void command(double v, double omega);

  const sim::Simulator& sim() const { return sim_; }
  const collision_avoidance::CollisionAvoidance& ca() const { return ca_; }
  const lld::OdometryInput& odometry() const { return odometry_; }
  const geometry::Pose2& truth() const { return truth_; }   // world frame, newest odometry sample
  int64_t truth_utime() const { return truth_utime_; }
  double true_distance() const { return true_distance_; }   // [m] driven since the start
  // Collision avoidance stands without a way to its targets (blocked or its reactive fallback).
  bool cannot_pass() const;
  // What the robot hit since the last call (the simulator's names: "lab.table.top", "person p2").
  std::vector<std::string> take_contacts();
  // [m] from the robot's centre to the nearest person's edge (infinity: nobody).
  double nearest_person() const;

 private:
  const lld::LldOptions& lld_;
  sim::Simulator sim_;
  sim::TimedCommandSource cmd_;
  lld::Follower follower_;
  collision_avoidance::CollisionAvoidance ca_;
  sim::StepOutput out_;
  lld::OdometryInput odometry_;
  bool have_odometry_ = false;
  geometry::Pose2 truth_;
  int64_t truth_utime_ = 0;
  double true_distance_ = 0;
  int64_t last_trajectory_id_ = 0;
  std::vector<std::string> contacts_;
};

}  // namespace rgnav::plan_eval
