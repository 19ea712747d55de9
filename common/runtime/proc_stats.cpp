#include "runtime/proc_stats.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>

namespace rgnav::runtime {
namespace {

double cpu_seconds()
{
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  auto tv = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return tv(ru.ru_utime) + tv(ru.ru_stime);
}

}  // namespace

ProcStats::ProcStats() : last_wall_(std::chrono::steady_clock::now()), last_cpu_s_(cpu_seconds()) {}

float ProcStats::cpu_percent()
{
  const auto now = std::chrono::steady_clock::now();
  const double cpu = cpu_seconds();
  const double wall = std::chrono::duration<double>(now - last_wall_).count();
  const double pct = wall > 0 ? 100.0 * (cpu - last_cpu_s_) / wall : 0.0;
  last_wall_ = now;
  last_cpu_s_ = cpu;
  return static_cast<float>(pct);
}

int64_t ProcStats::rss_kb()
{
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long pages_total = 0, pages_resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &pages_total, &pages_resident);
  std::fclose(f);
  if (n != 2) return 0;
  return static_cast<int64_t>(pages_resident) * sysconf(_SC_PAGESIZE) / 1024;
}

}  // namespace rgnav::runtime
