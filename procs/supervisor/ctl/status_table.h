// The controller's view: the newest SUPERVISOR_STATUS of every deputy as a text table.
#pragma once

#include <map>
#include <string>

#include "rgnav/supervisor_status_t.hpp"

namespace rgnav::supervisor {

const char* process_state_name(int8_t state);
// One block per host, one row per process.
std::string format_status(const std::map<std::string, supervisor_status_t>& by_host, int64_t now_utime);

}  // namespace rgnav::supervisor
