#include "proc_info.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

namespace rgnav::supervisor {

namespace {

std::optional<ProcStat> read_stat_file(const std::string& path)
{
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  // The command name is in parentheses and may itself hold spaces and ')'.
  const auto close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream rest(line.substr(close + 2));
  ProcStat s;
  std::string skip;
  // Fields from 3 on: state ppid pgrp session tty_nr tpgid flags minflt cminflt majflt
  // cmajflt utime stime cutime cstime priority nice num_threads itrealvalue starttime
  rest >> s.state >> s.ppid >> s.pgrp;
  for (int i = 0; i < 8; ++i) rest >> skip;
  uint64_t utime = 0, stime = 0;
  rest >> utime >> stime;
  for (int i = 0; i < 6; ++i) rest >> skip;
  rest >> s.start_ticks;
  if (!rest) return std::nullopt;
  s.cpu_ticks = utime + stime;
  return s;
}

}  // namespace

std::optional<ProcStat> read_proc_stat(pid_t pid) { return read_stat_file("/proc/" + std::to_string(pid) + "/stat"); }

char main_thread_state(pid_t pid)
{
  // The main thread's task has the process's id.
  const auto s = read_stat_file("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/stat");
  return s ? s->state : '?';
}

std::vector<std::string> read_cmdline(pid_t pid)
{
  std::ifstream in("/proc/" + std::to_string(pid) + "/cmdline", std::ios::binary);
  std::vector<std::string> out;
  std::string arg;
  while (std::getline(in, arg, '\0')) out.push_back(arg);
  return out;
}

int64_t read_rss_kb(pid_t pid)
{
  std::ifstream in("/proc/" + std::to_string(pid) + "/statm");
  int64_t size = 0, resident = 0;
  if (!(in >> size >> resident)) return 0;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

bool same_process_alive(pid_t pid, uint64_t start_ticks)
{
  if (pid <= 0) return false;
  const auto s = read_proc_stat(pid);
  return s && s->start_ticks == start_ticks && s->state != 'Z' && s->state != 'X';
}

float CpuMeter::sample(pid_t pid, uint64_t cpu_ticks, std::chrono::steady_clock::time_point now)
{
  auto it = last_.find(pid);
  float pct = 0.0f;
  if (it != last_.end()) {
    const double dt = std::chrono::duration<double>(now - it->second.when).count();
    const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
    if (dt > 0 && cpu_ticks >= it->second.ticks) pct = static_cast<float>(100.0 * (cpu_ticks - it->second.ticks) / hz / dt);
  }
  last_[pid] = {cpu_ticks, now};
  return pct;
}

}  // namespace rgnav::supervisor
