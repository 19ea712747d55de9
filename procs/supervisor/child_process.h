// Starting and signalling supervised processes. Each child runs in its own session (setsid),
// so it survives the supervisor (which re-adopts it after a restart) and can be signalled
// as a whole process group. A child holds an exclusive flock on its lock file for as long
// as it lives: a second instance of the same process on this host cannot be started, by
// this supervisor or another, so no device ever has two owners.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rgnav::supervisor {

struct SpawnRequest
{
  std::string executable;  // resolved path
  std::vector<std::string> argv;
  std::vector<std::pair<std::string, std::string>> env;  // added to the inherited environment
  std::string lock_path;   // "" = no lock
};

struct SpawnResult
{
  pid_t pid = 0;              // 0 on failure
  uint64_t start_ticks = 0;
  std::string error;          // why it did not start
  pid_t lock_holder = 0;      // the pid in the lock file when the lock was held
  uint64_t lock_holder_start_ticks = 0;
};

SpawnResult spawn_child(const SpawnRequest& request);

// Signals the child's process group (falls back to the pid alone). False if it is gone.
bool signal_child(pid_t pid, int sig);

// Holder recorded in a lock file ("pid start_ticks"), if the lock is held right now.
std::optional<std::pair<pid_t, uint64_t>> lock_holder(const std::string& lock_path);

// "exit 1", "signal 9 (Killed)", from a waitpid status.
std::string describe_wait_status(int status);

// An exclusive lock the calling process itself holds (one supervisor per host).
class SelfLock
{
 public:
  explicit SelfLock(const std::string& path);  // throws std::runtime_error naming the holder
  ~SelfLock();
  SelfLock(const SelfLock&) = delete;
  SelfLock& operator=(const SelfLock&) = delete;

 private:
  int fd_ = -1;
};

// mkdir -p; throws std::runtime_error.
void make_dirs(const std::string& path);

}  // namespace rgnav::supervisor
