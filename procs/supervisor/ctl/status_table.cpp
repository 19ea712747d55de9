#include "status_table.h"

#include <cstdio>

namespace rgnav::supervisor {

const char* process_state_name(int8_t state)
{
  switch (state) {
    case process_status_t::STATE_STOPPED: return "stopped";
    case process_status_t::STATE_STARTING: return "starting";
    case process_status_t::STATE_RUNNING: return "running";
    case process_status_t::STATE_HUNG: return "HUNG";
    case process_status_t::STATE_BACKOFF: return "backoff";
    case process_status_t::STATE_FAILED: return "FAILED";
    case process_status_t::STATE_STOPPING: return "stopping";
  }
  return "?";
}

std::string format_status(const std::map<std::string, supervisor_status_t>& by_host, int64_t now_utime)
{
  std::string out;
  char line[512];
  for (const auto& [host, s] : by_host) {
    const double age_s = (now_utime - s.utime) / 1e6;
    std::snprintf(line, sizeof line, "host %s  (%s, status %.1f s old)%s\n", host.c_str(), s.config.c_str(), age_s,
                  s.robot_held ? "  ROBOT HELD" : "");
    out += line;
    if (!s.alert.empty()) out += "  alert: " + s.alert + "\n";
    std::snprintf(line, sizeof line, "  %-20s %-16s %-9s %7s %4s %8s %6s %8s  %s\n", "NAME", "GROUP", "STATE", "PID", "RST",
                  "HB_AGE", "CPU%", "RSS_MB", "LAST EXIT");
    out += line;
    for (const auto& p : s.processes) {
      char hb[32];
      if (p.heartbeat_age_us < 0) {
        std::snprintf(hb, sizeof hb, "-");
      } else {
        std::snprintf(hb, sizeof hb, "%.0fms", p.heartbeat_age_us / 1000.0);
      }
      std::snprintf(line, sizeof line, "  %-20s %-16s %-9s %7d %4d %8s %6.1f %8.1f  %s\n", p.name.c_str(), p.group.c_str(),
                    p.state == process_status_t::STATE_STOPPED && p.last_exit.rfind("done", 0) == 0 ? "done" : process_state_name(p.state), p.pid, p.restarts, hb, p.cpu_percent, p.rss_kb / 1024.0,
                    p.last_exit.c_str());
      out += line;
    }
  }
  if (by_host.empty()) out = "no deputy status received\n";
  return out;
}

}  // namespace rgnav::supervisor
