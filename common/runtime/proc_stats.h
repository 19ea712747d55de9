// CPU share and resident memory of this process, for heartbeats.
#pragma once

#include <chrono>
#include <cstdint>

namespace rgnav::runtime {

class ProcStats
{
 public:
  ProcStats();
  // CPU time used since the previous call, in percent of one core over the wall time between.
  float cpu_percent();
  static int64_t rss_kb();

 private:
  std::chrono::steady_clock::time_point last_wall_;
  double last_cpu_s_ = 0;
};

}  // namespace rgnav::runtime
