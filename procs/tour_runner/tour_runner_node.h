// Node adapter of the tour runner: odometry (and laser) in; TARGETS for collision avoidance,
// or BASE_CMD from the simple follower, out. Ends the run when the tour is done.
#pragma once

#include <optional>
#include <string>

#include "config/robot_description.h"
#include "procs/tour_runner/pure_pursuit.h"
#include "procs/tour_runner/tour.h"
#include "procs/tour_runner/tour_sequencer.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/slam_pose_t.hpp"
#include "runtime/node.h"

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

struct Channels
{
  std::string odometry = "ODOMETRY";
  std::string laser = "LASER_FRONT";
  std::string slam_pose = "SLAM_POSE";  // "" = steer on odometry alone (it drifts)
  std::string targets = "TARGETS";
  std::string base_cmd = "BASE_CMD";
};

// The laser mounting pose and the follower's robot radius are the robot description's.
TourRunnerOptions load_options(const config::Config& tour_section, const config::Config& follower_section,
                               const config::RobotDescription& robot, const std::string& config_dir);
Channels load_channels(const config::Config& section);

class TourRunnerNode
{
 public:
  TourRunnerNode(runtime::Node& node, const TourRunnerOptions& options, const Channels& channels);

 private:
  void on_odometry(const odometry_t& m);
  void on_scan(const laser_scan_t& m);
  void on_slam_pose(const slam_pose_t& m);
  void publish_targets(int64_t utime);
  void publish_cmd(int64_t utime, double v, double omega);

  runtime::Node& node_;
  const TourRunnerOptions options_;
  const Channels channels_;
  // Frames: the tour is in the world frame; the map frame of the scan mapper is the odometry
  // frame at its first scan, i.e. the start pose. Odometry drifts (percent of the distance,
  // and heading bias per metre), so after a few rooms odometry-frame targets miss the doors;
  // the scan mapper's correction map_from_odom keeps the targets where the doors are.
  geometry::Pose2 map_from_world_;
  geometry::Pose2 odom_from_map_;           // identity until the first SLAM_POSE
  std::optional<TourSequencer> sequencer_;  // targets in the map frame
  std::vector<Eigen::Vector2d> world_targets_;
  std::vector<Eigen::Vector2d> obstacles_;
  int64_t last_scan_utime_ = 0;
  int64_t cmd_seq_ = 0;
  bool finished_ = false;
  bool blocked_ = false;   // last state logged, to log transitions only
  struct Escape
  {
    geometry::Pose2 odom_start;
    double odom_heading = 0;  // committed free heading, odom frame
    int64_t start_utime = 0;
  };
  std::optional<Escape> escape_;
};

}  // namespace rgnav::tour_runner
