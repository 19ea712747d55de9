// Options of the laser_driver process, read and validated from config/laser_driver.yaml
// (section `laser_driver`, channel names from `channels`) and the robot description (mounting).
#pragma once

#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "lms2xx_driver.h"

namespace rgnav::drivers::sick {

// Where the laser sits on the robot (robot frame: x forward, y left, z up): the robot
// description's laser_front. laser_scan_t is in the laser frame, so consumers take the pose
// from the robot description too; the driver logs it at start.
struct MountingPose
{
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.4;
  double yaw_rad = 0.0;
};

struct LaserDriverOptions
{
  DriverOptions driver;
  std::string sensor = "laser_front";
  std::string channel = "LASER_FRONT";
  MountingPose mounting;
};

// Throws config::ConfigError naming the file and key.
LaserDriverOptions load_laser_driver_options(const config::Config& section, const config::Config& channels,
                                             const config::RobotDescription& robot);

}  // namespace rgnav::drivers::sick
