// The scan mapper's options for offline mapping (rgnav_map, the RG map pipeline, the SLAM
// benchmark): section `scan_mapper` of the process's own config file, read by the process's own
// loader, with the same unknown-key check (the live process's sections — node, channels,
// persistence — are checked when it starts).
#pragma once

#include <string>

#include "scan_mapper/scan_mapper_options.h"

namespace rgnav::scan_mapper {

// The laser mounting pose is the robot description's. Throws config::ConfigError naming the file
// and key.
ScanMapperOptions load_offline_options(const std::string& config_path, const config::RobotDescription& robot);

}  // namespace rgnav::scan_mapper
