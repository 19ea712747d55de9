// Reads procman sheriff configuration files (libbot2 bot2-procman grammar):
//
//   # comment
//   cmd "name" { exec = "..."; host = "..."; auto_respawn = "true"; stop_signal = 15;
//                stop_time_allowed = 7; }
//   group "name" { cmd "x" { ... } group "sub" { ... } }
//   script "name" { start cmd "x" wait "running"; wait ms 500; stop group "g";
//                   restart everything; wait cmd "x" status "running"; run_script "y"; }
//
// plus the rgnav attributes of a cmd (values are strings unless noted):
//   depends = "sim,laser_driver";  env = "K=V,K2=V2";  config = "config/x.yaml";
//   heartbeat = "false";  heartbeat_timeout_ms = 800;  startup_timeout_ms = 5000;  work_timeout_ms = 3000;
//   inputs = "LASER_FRONT,ODOMETRY";  safety_critical = "true";
//   oneshot = "true";   (a job: exit 0 is "done", never restarted; dependents may then start)
// config and exec expand ${VAR} from the supervisor's environment (RGNAV_ROOT, RGNAV_BUILD, ...).
// Syntax errors throw LaunchError naming file:line.
#pragma once

#include <stdexcept>
#include <string>

#include "launch_config.h"

namespace rgnav::supervisor {

class LaunchError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

// Throws LaunchError naming the file: missing, empty, binary, a syntax error (with its line), or
// no command at all (a file cut off in its header, or no launch config).
LaunchConfig parse_launch_file(const std::string& path);
// `origin` names the text in messages.
LaunchConfig parse_launch_text(const std::string& text, const std::string& origin);

}  // namespace rgnav::supervisor
