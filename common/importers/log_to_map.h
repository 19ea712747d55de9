// The start of every offline mapping tool (rgnav_map, rgnav_rgmap_offline): read the LCM log,
// report what was skipped in it, and refuse a log with nothing to map rather than write an
// empty map.
#pragma once

#include <iostream>
#include <optional>
#include <string>

#include "importers/lcm_log_io.h"

namespace rgnav::importers {

// read_lcm_log(path) with its issues on stderr, one a line naming the file and the event; no
// value (after saying so on stderr under `tool`'s name) when the log holds no LASER_FRONT scan.
// Throws as read_lcm_log does.
inline std::optional<ImportedLog> read_log_to_map(const std::string& path, const std::string& tool)
{
  auto log = read_lcm_log(path);
  for (const auto& i : log.issues) std::cerr << path << ": event " << i.line << ": " << i.what << "\n";
  if (log.scans.empty()) {
    std::cerr << tool << ": " << path << ": no LASER_FRONT scans in its " << log.lines << " events, nothing to map\n";
    return std::nullopt;
  }
  return log;
}

}  // namespace rgnav::importers
