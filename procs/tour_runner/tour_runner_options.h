// Options of the tour runner (config/tour_runner.yaml, sections `tour` and `follower`),
// loaded and validated outside the node and held const inside it.
#pragma once

#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "geometry/pose2.h"
#include "procs/tour_runner/pure_pursuit.h"
#include "procs/tour_runner/tour_sequencer.h"

namespace rgnav::tour_runner {

struct TourRunnerOptions
{
  std::string tour_file;
  double max_spacing = 1.5;        // [m] between consecutive targets
  SequencerOptions sequencer;
  enum class Output { kTargets, kBaseCmd } output = Output::kBaseCmd;
  bool exit_when_done = true;
  double max_speed = 0.5;          // [m/s] handed on with TARGETS
  PursuitOptions follower;
  geometry::Pose2 base_from_laser{0.12, 0.0, 0.0};
  double scan_stale_s = 0.5;       // [s] message-time age of the newest scan that stops the follower
  int32_t cmd_deadline_us = 200'000;
};

// Relative tour files resolve against config_dir. The laser mounting pose and the follower's
// robot radius are the robot description's.
TourRunnerOptions load_options(const config::Config& tour_section, const config::Config& follower_section,
                               const config::RobotDescription& robot, const std::string& config_dir);

}  // namespace rgnav::tour_runner
