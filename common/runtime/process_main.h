// The body of every process's main(): common flags, logging, config validation, the Node,
// the loop, and exit codes. A process main is then
//
//   int main(int argc, char** argv)
//   {
//     return rgnav::runtime::process_main(argc, argv, "scan_mapper", [](ProcessContext& ctx) {
//       auto options = scan_mapper::load_options(ctx.config.section("scan_mapper"), ctx.robot);
//       return std::make_shared<ScanMapperNode>(ctx.node, options, ctx.config.section("channels"));
//     });
//   }
//
// Exit codes: 0 clean stop (SIGINT/SIGTERM), 1 runtime failure, 2 bad command line or config
// (the message names the file and key).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "runtime/node.h"

namespace CLI { class App; }

namespace rgnav::runtime {

struct ProcessContext
{
  const config::Config& config;
  // The robot description (--robot): geometry, drive limits and sensor mounting for the
  // options loaders, which take it from here rather than from copies in the process config.
  const config::RobotDescription& robot;
  Node& node;
  std::string config_path;
  // --check-config: build everything to validate it, but touch no devices, files or threads
  // (open no journal, no serial port, start no control loop).
  bool checking_only = false;
};

// Returns whatever must stay alive while the node runs (the node adapter).
using ProcessSetup = std::function<std::shared_ptr<void>(ProcessContext&)>;

// Flags: --config FILE (default <config dir>/<name>.yaml), --robot FILE (default
// default_robot_path(config)), --lcm-url URL, --name NAME, --log-level LEVEL, --check-config
// (validate the config and the robot description, then exit). add_flags may add more.
int process_main(int argc, char** argv, const std::string& default_name, const ProcessSetup& setup,
                 const std::function<void(CLI::App&)>& add_flags = nullptr);

// $RGNAV_CONFIG_DIR, else config/ of the source tree this binary was built from.
std::string default_config_dir();
// robot.yaml beside `config_path` if there is one, else <config dir>/robot.yaml (a process
// config written elsewhere, e.g. by a test harness, still describes the same robot).
std::string default_robot_path(const std::string& config_path);
// $RGNAV_DATA_DIR, else ../shared/data beside the source tree (the shared real data sets).
std::string default_data_dir();

}  // namespace rgnav::runtime
