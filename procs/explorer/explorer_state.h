// What an explorer keeps across a restart (--state-file): Explorer::save()'s document (the
// gateway stack, visited frontier places, the start region, the phase, the goal counter) with
// the message time it was saved at, in the checkpoint framing of common/persist (written
// atomically: the old file or the new one, never half of one; a damaged one is detected on
// reading).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace rgnav::explorer {

struct ExplorerState
{
  int64_t utime = 0;          // [us] message time it was saved at
  nlohmann::json explorer;    // Explorer::save()
};

// Throws std::runtime_error when the file cannot be written (the old one is then untouched).
void save_explorer_state(const std::string& path, const ExplorerState& state);
// nullopt when there is no file; throws std::runtime_error naming the file and what is wrong
// (damaged, not an explorer state). The explorer's document itself is checked by
// Explorer::restore.
std::optional<ExplorerState> load_explorer_state(const std::string& path);

}  // namespace rgnav::explorer
