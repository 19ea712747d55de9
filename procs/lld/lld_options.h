// Options of the low-level drive, loaded and validated from config/lld.yaml.
#pragma once

#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "lld/follower.h"

namespace rgnav::lld {

struct LoopOptions
{
  double rate_hz = 20.0;          // control rate (diss. 5.5.3: "about twenty times per second")
  int realtime_priority = 40;     // SCHED_FIFO priority when permitted (0: do not ask)
  bool lock_memory = true;        // mlockall when permitted
  int command_deadline_ms = 150;  // BASE_CMD void after this (3 periods at 20 Hz)
  int idle_commands = 10;         // zero commands still sent after coming to rest
};

struct ChannelOptions
{
  std::string trajectory = "TRAJECTORY";
  std::string odometry = "ODOMETRY";
  std::string command = "BASE_CMD";
  std::string status = "LLD_STATUS";
};

struct LldOptions
{
  LoopOptions loop;
  ChannelOptions channels;
  FollowerOptions follower;
  double stall_excuse_max_s = 0.4;   // [s] longest host stall not held against the odometry (stall_credit.h)
};

// Reads the `channels`, `loop`, `tracking`, `limits` and `timeouts` sections; the drive's
// acceleration limits are the robot description's, and the lld's speeds must stay within its.
LldOptions load_lld_options(const config::Config& root, const config::RobotDescription& robot);

}  // namespace rgnav::lld
