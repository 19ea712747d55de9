// A saved RG map on disk: an rgmap.json, a JSON document whose first member checks the rest
// (common/persist/checked_json.h), as the RG kernel and ./rgnav map write it, or a folder holding one. Processes
// that run on a saved map (localizer, planner) load it with load_saved_map; the operator's
// tools that change it (./rgnav name-region --map) write it back with save_map, atomically.
#pragma once

#include <string>

#include "rgmap/rg_map.h"

namespace rgnav::rgmap {

// `path` itself, or <path>/rgmap.json when it is a folder.
std::string saved_map_file(const std::string& path);
// Throws std::runtime_error naming the file and what is wrong with it (missing, damaged, not
// an RG map).
RgMap load_saved_map(const std::string& path);
// load_saved_map for a process's --map flag: throws config::ConfigError ("--map: ...") so that
// the process refuses to start with the reason.
RgMap load_map_flag(const std::string& path);
// Writes `map` to saved_map_file(path) atomically (the old file stays whole if this fails);
// throws std::runtime_error on failure.
void save_map(const RgMap& map, const std::string& path);

}  // namespace rgnav::rgmap
