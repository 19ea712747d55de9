// The supervisor's record of the children it started (pid, start time, argv), rewritten
// atomically whenever a child starts or ends, so a supervisor that was killed and restarted
// can tell its still-running children from strangers that reuse their pids, and adopt them.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rgnav::supervisor {

struct ChildRecord
{
  std::string name;
  pid_t pid = 0;
  uint64_t start_ticks = 0;
  std::vector<std::string> argv;
  int stop_signal = 15;
  int restarts = 0;
};

struct SupervisorState
{
  std::string host;
  std::string launch_config;
  std::vector<ChildRecord> children;
  // Oneshot jobs that finished in this launch: a successor (after a crash) must not run a
  // finished tour again. A clean shutdown clears the list.
  std::vector<std::string> done;
};

// Missing file: empty state. A damaged one (not JSON, not a state, empty, binary) is moved to
// <path>.damaged with an error in the log naming it, and the state is empty.
SupervisorState load_state(const std::string& path);
// Write to path.tmp, fsync, rename. Throws std::runtime_error.
void save_state(const std::string& path, const SupervisorState& state);

}  // namespace rgnav::supervisor
