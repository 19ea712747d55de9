#include "runtime/process_main.h"

#include <CLI/CLI.hpp>

#include <cstdlib>
#include <iostream>

#include "bus/fake_bus.h"
#include "bus/lcm_bus.h"
#include "log/log.h"

#ifndef RGNAV_SOURCE_DIR
#error "RGNAV_SOURCE_DIR must be defined by the build"
#endif

namespace rgnav::runtime {

std::string default_config_dir()
{
  if (const char* dir = std::getenv("RGNAV_CONFIG_DIR"); dir && *dir) return dir;
  return std::string(RGNAV_SOURCE_DIR) + "/config";
}

std::string default_robot_path(const std::string& config_path)
{
  return config::robot_path_beside(config_path, default_config_dir() + "/robot.yaml");
}

std::string default_data_dir()
{
  if (const char* dir = std::getenv("RGNAV_DATA_DIR"); dir && *dir) return dir;
  return std::string(RGNAV_SOURCE_DIR) + "/../shared/data";
}

int process_main(int argc, char** argv, const std::string& default_name, const ProcessSetup& setup,
                 const std::function<void(CLI::App&)>& add_flags)
{
  CLI::App app{"rgnav process " + default_name};
  std::string config_path = default_config_dir() + "/" + default_name + ".yaml";
  std::string robot_path;
  std::string lcm_url;
  std::string name;
  std::string log_level = "info";
  bool check_only = false;
  app.add_option("--config", config_path, "process config (YAML)");
  app.add_option("--robot", robot_path, "robot description (YAML; default: robot.yaml beside the config)");
  app.add_option("--lcm-url", lcm_url, "LCM URL, overrides node.lcm_url");
  app.add_option("--name", name, "process name, overrides node.name");
  app.add_option("--log-level", log_level, "trace|debug|info|warn|error");
  app.add_flag("--check-config", check_only, "validate the config and exit");
  if (add_flags) add_flags(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }

  try {
    log::init(name.empty() ? default_name : name, log_level);
  } catch (const std::exception& e) {
    std::cerr << default_name << ": " << e.what() << "\n";
    return 2;
  }

  try {
    const auto cfg = config::Config::load(config_path);
    if (robot_path.empty()) robot_path = default_robot_path(config_path);
    const auto robot = config::load_robot_description_file(robot_path);
    NodeOptions node_options = load_node_options(cfg.section("node"), default_name);
    if (!name.empty()) node_options.name = name;
    if (!lcm_url.empty()) node_options.lcm_url = lcm_url;
    if (check_only) {
      // Build everything but the bus: a config check must not need a network.
      Node node(node_options, std::make_unique<bus::FakeBus>());
      ProcessContext ctx{cfg, robot, node, config_path, true};
      auto keep = setup(ctx);
      cfg.finish();
      std::cout << config_path << " (robot " << robot_path << "): ok\n";
      return 0;
    }
    Node node(node_options);
    ProcessContext ctx{cfg, robot, node, config_path};
    auto keep = setup(ctx);
    cfg.finish();
    return node.run();
  } catch (const config::ConfigError& e) {
    spdlog::critical("refusing to start: {}", e.what());
    return 2;
  } catch (const bus::BusError& e) {
    spdlog::critical("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::critical("fatal: {}", e.what());
    return 1;
  }
}

}  // namespace rgnav::runtime
