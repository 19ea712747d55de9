// Process logging: spdlog's default logger, to stderr, each line tagged with the process name
// so the interleaved output of a launched stack stays readable.
#pragma once

#include <spdlog/spdlog.h>

#include <string>

namespace rgnav::log {

// level: trace, debug, info, warn, error, critical, off. Throws std::invalid_argument on an
// unknown level name.
void init(const std::string& process_name, const std::string& level = "info");

}  // namespace rgnav::log
