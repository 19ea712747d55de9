// Snapshots of the mapper state: written atomically and checked (persist/atomic_file.h: temp
// file, fsync, rename; header with length and CRC-32), with a magic and a version inside. A
// damaged, foreign or non-finite snapshot is refused, never half-loaded. Between snapshots,
// the journal (mapper_store.h) holds what changed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "scan_mapper/scan_ids.h"
#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

struct PersistedState
{
  MapperState mapper;
  ScanIdState ids;
  uint64_t last_record = 0;  // sequence number of the newest journal record it includes
};

std::string encode_snapshot(const PersistedState& state);
// Throws persist::CorruptBytes (persist/byte_codec.h) when the bytes are not a complete, finite snapshot.
PersistedState decode_snapshot(const std::string& bytes);

// Throws std::runtime_error when the file cannot be written or the state is not finite.
void save_snapshot(const PersistedState& state, const std::string& path);
// nullopt when the file does not exist; throws std::runtime_error (naming the file and the
// defect) when it exists but is unreadable, truncated, corrupt or of another version.
std::optional<PersistedState> load_snapshot(const std::string& path);

// The mapper state alone (offline tools, tests).
void save_state(const MapperState& state, const std::string& path);
std::optional<MapperState> load_state(const std::string& path);

}  // namespace rgnav::scan_mapper
