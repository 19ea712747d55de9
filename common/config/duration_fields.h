// Durations in config files are whole milliseconds under keys named *_ms; this reads one into
// a std::chrono::milliseconds field, its current value the default:
//
//   d.pdo_timeout = config::milliseconds(drives, "pdo_timeout_ms", d.pdo_timeout, 10, 5000);
//
// Out of [min, max] (in ms) it is an error naming the file and key, as Config::integer's is.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "config/config.h"

namespace rgnav::config {

inline std::chrono::milliseconds milliseconds(const Config& c, const std::string& key, std::chrono::milliseconds def,
                                              int64_t min, int64_t max)
{
  return std::chrono::milliseconds(c.integer(key, def.count(), min, max));
}

}  // namespace rgnav::config
