// Persisting the mapper state so a restarted scan mapper resumes its map. The file is written
// atomically (temp file, fsync, rename, fsync of the directory) and carries a magic, a
// version and a checksum; a damaged or foreign file is refused, never half-loaded.
#pragma once

#include <optional>
#include <string>

#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

// Throws std::runtime_error when the file cannot be written.
void save_state(const MapperState& state, const std::string& path);

// nullopt when the file does not exist; throws std::runtime_error (with the reason) when it
// exists but is unreadable, truncated, corrupt or of another version.
std::optional<MapperState> load_state(const std::string& path);

}  // namespace rgnav::scan_mapper
