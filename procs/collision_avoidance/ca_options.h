// Options of collision avoidance, loaded and validated from config/collision_avoidance.yaml;
// the robot's radius and laser mounting pose come from the robot description.
#pragma once

#include <string>

#include "collision_avoidance/collision_avoidance.h"
#include "config/config.h"
#include "config/robot_description.h"

namespace rgnav::collision_avoidance {

struct CaChannels
{
  std::string targets = "TARGETS";
  std::string nav_goal = "NAV_GOAL";
  std::string odometry = "ODOMETRY";
  std::string laser = "LASER_FRONT";
  std::string obstacles = "OBSTACLES_3D";
  std::string lld_status = "LLD_STATUS";
  std::string trajectory = "TRAJECTORY";
  std::string status = "CA_STATUS";   // mode and blocked time, for the planner ("" = not published)
};

struct CaNodeOptions
{
  CaChannels channels;
  CaOptions ca;
};

CaNodeOptions load_ca_options(const config::Config& root, const config::RobotDescription& robot);

}  // namespace rgnav::collision_avoidance
