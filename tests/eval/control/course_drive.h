// One obstacle course driven in lock-step: the simulated B21r, collision avoidance and the lld
// follower, 50 ms per step, the course's targets handed to collision avoidance in the world
// frame and re-expressed in the drifting odometry frame through a perfect localizer. What
// control_bench's obstacle courses measure, and what the vision's course bench drives with and
// without its grid (a hook sees every simulator step and may feed collision avoidance more).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <string>

#include "collision_avoidance/ca_options.h"
#include "collision_avoidance/collision_avoidance.h"
#include "config/robot_description.h"
#include "lld/lld_options.h"
#include "sim/simulator.h"

#include "obstacle_course.h"

namespace rgnav::bench {

struct CourseDriveOptions
{
  sim::SimulatorOptions sim;   // control_sim_options(seed, true) and whatever robot the caller measures
  double time_limit_s = 120.0;
  double max_speed = 0.6;      // [m/s] the targets' speed limit
  // Called after each simulator step, once its odometry and scans went to collision avoidance
  // and before it decides (may feed it more, e.g. an OBSTACLES_3D grid).
  std::function<void(const sim::Simulator&, const sim::StepOutput&, collision_avoidance::CollisionAvoidance&)> after_step;
  bool trace = false;          // CB_DEBUG: a line every 0.5 s and one per contact
  bool trace_nearest = false;  // CB_DEBUG_NEAREST: the nearest obstacle points every step
};

struct CourseDriveResult
{
  bool arrived = false;
  double time_s = 0.0;        // simulated, at arrival or the time limit
  int64_t collisions = 0;
  int64_t fallbacks = 0;
  int64_t replans = 0;
  sim::Pose2 end;             // true pose at the end
  std::string mode;           // collision avoidance's mode at the end
  nlohmann::json contacts = nlohmann::json::array();  // contact_json of each contact, with "course": index
};

// The robot description and the shipped lld and collision avoidance options, loaded and checked
// as their processes load them (unknown keys refused; the `node` sections are the processes').
struct DriveConfig
{
  config::RobotDescription robot;
  lld::LldOptions lld;
  collision_avoidance::CaNodeOptions ca;
};
DriveConfig load_drive_config(const std::string& config_dir);

CourseDriveResult drive_course(const Course& course, int index, const lld::LldOptions& lld_options,
                               const collision_avoidance::CaOptions& ca_options, const CourseDriveOptions& options);

}  // namespace rgnav::bench
