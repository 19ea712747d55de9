// Real-time scheduling for the processes whose timing the robot's safety rests on: the
// lld's 20 Hz loop, the base driver's CAN thread (drive heartbeats and the deadman) and the
// simulated drives standing in for the drives' firmware. Under a loaded machine (compilers,
// the mapper's optimisation) normal scheduling delayed CAN heartbeats past the 60 ms the
// drive supervision allows and stopped the robot for nothing.
#pragma once

#include <string>
#include <string_view>

namespace rgnav::runtime {

// Asks for SCHED_FIFO at `priority` for the calling thread (0: do not ask) and, if
// lock_memory, locks the process's memory (mlockall). Returns a one-line description of
// what was granted or refused, for the caller to log once; *granted tells whether all was.
std::string request_realtime(int priority, bool lock_memory, bool* granted);

// request_realtime for the calling thread, logged once as "<thread>: <what>": at info level when
// granted, else as a warning with `if_refused` (what may go wrong without it) in brackets.
// Returns whether all was granted.
bool request_realtime_logged(std::string_view thread, int priority, bool lock_memory, std::string_view if_refused = {});

}  // namespace rgnav::runtime
