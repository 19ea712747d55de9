// What /proc says about a process: identity (start time, command line) to tell a process
// from a later one that reuses its pid, liveness, and load (cpu, rss) for the status.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rgnav::supervisor {

struct ProcStat
{
  char state = '?';          // R, S, D, T (stopped), Z (zombie), ...
  int ppid = 0;
  int pgrp = 0;
  uint64_t cpu_ticks = 0;    // utime + stime [clock ticks]
  uint64_t start_ticks = 0;  // since boot [clock ticks]; with the pid, identifies a process
};

std::optional<ProcStat> read_proc_stat(pid_t pid);
// The state letter of the process's main thread (the one running its event loop): 'D' while
// it waits on the disk (an fsync on a loaded disk), '?' if unknown.
char main_thread_state(pid_t pid);
std::vector<std::string> read_cmdline(pid_t pid);
int64_t read_rss_kb(pid_t pid);

// True if `pid` is the process that started at `start_ticks` and has not exited.
bool same_process_alive(pid_t pid, uint64_t start_ticks);

// CPU share of other processes between successive samples.
class CpuMeter
{
 public:
  // Percent of one core since the previous sample of this pid (0 on the first).
  float sample(pid_t pid, uint64_t cpu_ticks, std::chrono::steady_clock::time_point now);
  void forget(pid_t pid) { last_.erase(pid); }

 private:
  struct Last
  {
    uint64_t ticks;
    std::chrono::steady_clock::time_point when;
  };
  std::map<pid_t, Last> last_;
};

}  // namespace rgnav::supervisor
