#include "lld/loop_stats_json.h"

#include <fstream>
#include <sstream>

namespace rgnav::lld {

std::string loop_stats_json(const LoopStats& s)
{
  std::ostringstream o;
  o.precision(6);
  o << "{\"ticks\": " << s.ticks << ", \"overruns\": " << s.overruns << ", \"jitter_p50_ms\": " << s.jitter_p50_ms
    << ", \"jitter_p99_ms\": " << s.jitter_p99_ms << ", \"jitter_max_ms\": " << s.jitter_max_ms
    << ", \"jitter_mean_ms\": " << s.jitter_mean_ms << ", \"step_max_ms\": " << s.step_max_ms
    << ", \"long_steps\": " << s.long_steps << ", \"late_wakes\": " << s.late_wakes
    << ", \"minor_faults\": " << s.usage.minor_faults << ", \"major_faults\": " << s.usage.major_faults
    << ", \"involuntary_switches\": " << s.usage.involuntary_switches << ", \"stalls\": [";
  for (size_t i = 0; i < s.stalls.size(); ++i) {
    const Stall& st = s.stalls[i];
    o << (i ? ", " : "") << "{\"wake_ns\": " << st.wake_ns << ", \"jitter_ms\": " << st.jitter_ms
      << ", \"late_ms\": " << st.late_ms << ", \"step_ms\": " << st.step_ms
      << ", \"step_overran\": " << (st.step_overran ? "true" : "false") << ", \"missed\": " << st.missed
      << ", \"minor_faults\": " << st.usage.minor_faults << ", \"major_faults\": " << st.usage.major_faults
      << ", \"involuntary_switches\": " << st.usage.involuntary_switches << "}";
  }
  o << "]}\n";
  return o.str();
}

bool write_loop_stats(const std::string& path, const LoopStats& s)
{
  std::ofstream out(path);
  out << loop_stats_json(s);
  return static_cast<bool>(out);
}

}  // namespace rgnav::lld
