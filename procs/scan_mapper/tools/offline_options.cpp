#include "offline_options.h"

#include "config/finish_except.h"

namespace rgnav::scan_mapper {

ScanMapperOptions load_offline_options(const std::string& config_path, const config::RobotDescription& robot)
{
  const auto cfg = config::Config::load(config_path);
  const ScanMapperOptions options = load_scan_mapper_options(cfg.section("scan_mapper"), robot);
  config::finish_except(cfg, {"node", "channels", "persistence"});
  return options;
}

}  // namespace rgnav::scan_mapper
