// The robot description (config/robot.yaml): the one place for the robot's geometry, drive
// limits and sensor mounting. process_main loads it (--robot FILE) and hands it to every
// process's options loader, so no process config carries a copy of it.
//
//   const auto robot = config::load_robot_description_file("config/robot.yaml");
//   options.base_from_laser = robot.laser_front.base_from_laser;
#pragma once

#include <string>

#include "config/config.h"
#include "geometry/pose2.h"

namespace rgnav::config {

// Defaults are the B21r's (as config/robot.yaml); the file must give every value.
struct DriveLimits
{
  std::string kind = "synchro";  // synchro: translation and rotation commanded independently
  double max_v = 0.9;            // [m/s]
  double max_omega = 1.6;        // [rad/s]
  double max_accel = 0.6;        // [m/s^2]
  double max_alpha = 2.0;        // [rad/s^2]
};

struct LaserMount
{
  geometry::Pose2 base_from_laser{0.12, 0.0, 0.0};  // scan frame in the base frame
  double height = 0.40;                              // [m] scan plane above the floor
};

struct StereoHead
{
  geometry::Pose2 base_from_head;  // pan-tilt head in the base frame
  double height = 1.25;            // [m] cameras above the floor
  double baseline = 0.12;          // [m]
};

struct RobotDescription
{
  std::string name = "b21r";
  double radius = 0.26;  // [m] the footprint is a circle
  double height = 1.35;  // [m] top of the robot, for 3D obstacle filtering
  DriveLimits drive;
  LaserMount laser_front;
  StereoHead stereo;
};

// From a whole robot description file; every key is required. Does not call cfg.finish().
RobotDescription load_robot_description(const Config& cfg);
// Loads, reads and finishes `path`: an unknown key or bad value throws ConfigError naming both.
RobotDescription load_robot_description_file(const std::string& path);
// robot.yaml in the folder of `config_path` if it exists, else `fallback`: a process config
// and the robot it runs on are kept side by side (config/), wherever the tree is.
std::string robot_path_beside(const std::string& config_path, const std::string& fallback);

}  // namespace rgnav::config
