// The control loop's timing as JSON (lld --loop-stats, and the bench's canary loop): the
// figures deploy/bench/control.sh puts into logs/bench/control.json, and every stall with
// its CLOCK_MONOTONIC wake time so that stalls of different processes can be matched.
#pragma once

#include <string>

#include "lld/loop_timeline.h"

namespace rgnav::lld {

std::string loop_stats_json(const LoopStats& s);
// Writes loop_stats_json(s) to `path`; false if the file cannot be written.
bool write_loop_stats(const std::string& path, const LoopStats& s);

}  // namespace rgnav::lld
