// What a planner keeps across a restart (--state-file): what it learned about the RG graph's
// edges (EdgeCosts::to_json), the operator's region names (a planner on a saved map has no RG
// kernel to keep them), and the goal it was pursuing, so that a killed planner takes it up
// again. One JSON document in the checkpoint framing of common/persist (written atomically:
// the old file or the new one, never half of one; a damaged one is detected on reading).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "planner/planner.h"

namespace rgnav::planner {

struct PlannerState
{
  int64_t utime = 0;                          // [us] message time it was saved at
  nlohmann::json costs;                       // EdgeCosts::to_json (null: nothing learned)
  std::map<int64_t, std::string> names;       // region id -> the operator's name
  std::optional<NavGoal> goal;                // being pursued (active, or waiting for a path)
};

// Throws std::runtime_error when the file cannot be written (the old one is then untouched).
void save_planner_state(const std::string& path, const PlannerState& state);
// nullopt when there is no file; throws std::runtime_error naming the file and what is wrong
// (damaged, not a planner state, a bad value).
std::optional<PlannerState> load_planner_state(const std::string& path);

}  // namespace rgnav::planner
