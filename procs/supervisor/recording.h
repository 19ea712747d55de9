// Recording a launched stack with the real lcm-logger, as one more supervised command
// (restarted if it dies, stopped last), and the environment launch configs expand.
#pragma once

#include <map>
#include <string>

#include "launch_config.h"

namespace rgnav::supervisor {

// Adds command "lcm_logger" on `host`: lcm-logger into <dir>/rgnav.lcmlog (split every
// split_mb MB into .00, .01, ... with -i when split_mb > 0), on the given LCM URL.
void add_recorder(LaunchConfig& config, const std::string& host, const std::string& dir, double split_mb,
                  const std::string& lcm_url);

// RGNAV_ROOT (the source tree) and RGNAV_BUILD (the build folder holding bin/) as launch
// configs use them in exec lines; derived from this executable's location when not set.
std::map<std::string, std::string> launch_environment(const std::string& argv0);

}  // namespace rgnav::supervisor
