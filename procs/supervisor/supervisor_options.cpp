#include "supervisor_options.h"

#include <unistd.h>

#include <cstdlib>
#include <sstream>

#include "config/duration_fields.h"
#include "config/string_fields.h"

namespace rgnav::supervisor {

SupervisorOptions load_supervisor_options(const config::Config& s)
{
  SupervisorOptions o;
  o.heartbeat_timeout = config::milliseconds(s, "heartbeat_timeout_ms", o.heartbeat_timeout, 50, 600000);
  o.startup_timeout = config::milliseconds(s, "startup_timeout_ms", o.startup_timeout, 100, 600000);
  o.work_timeout = config::milliseconds(s, "work_timeout_ms", o.work_timeout, 50, 600000);
  o.disk_wait_timeout = config::milliseconds(s, "disk_wait_timeout_ms", o.disk_wait_timeout, 0, 600000);
  o.stall_threshold = config::milliseconds(s, "stall_threshold_ms", o.stall_threshold, 5, 60000);
  o.stall_window = config::milliseconds(s, "stall_window_ms", o.stall_window, 0, 60000);
  // Wider, a healthy process's newest heartbeat would fall in it (shared_silence.h).
  if (o.stall_window * 2 > o.heartbeat_timeout)
    s.fail("stall_window_ms", "must be at most half of heartbeat_timeout_ms (" + std::to_string(o.heartbeat_timeout.count()) +
                                  "): a healthy process's newest heartbeat would lie within it");
  o.stall_hold = config::milliseconds(s, "stall_hold_ms", o.stall_hold, 0, 10000);
  o.hung_grace = config::milliseconds(s, "hung_grace_ms", o.hung_grace, 0, 60000);
  o.tick = config::milliseconds(s, "tick_ms", o.tick, 1, 1000);
  o.status_period = config::milliseconds(s, "status_period_ms", o.status_period, 50, 60000);
  o.status_min_gap = config::milliseconds(s, "status_min_gap_ms", o.status_min_gap, 0, 60000);
  o.remote_fresh = config::milliseconds(s, "remote_fresh_ms", o.remote_fresh, 100, 600000);
  o.orphan_grace = config::milliseconds(s, "orphan_grace_ms", o.orphan_grace, 0, 600000);
  o.default_auto_respawn = s.boolean("default_auto_respawn", o.default_auto_respawn);
  const auto r = s.section("restart");
  o.restart.initial_backoff = config::milliseconds(r, "initial_backoff_ms", o.restart.initial_backoff, 0, 600000);
  o.restart.max_backoff = config::milliseconds(r, "max_backoff_ms", o.restart.max_backoff, 0, 3600000);
  if (o.restart.max_backoff < o.restart.initial_backoff) r.fail("max_backoff_ms", "must be >= initial_backoff_ms");
  o.restart.backoff_factor = r.number("backoff_factor", o.restart.backoff_factor, 1.0, 10.0);
  o.restart.max_restarts = static_cast<int>(r.integer("max_restarts", o.restart.max_restarts, 0, 1000));
  o.restart.window = config::milliseconds(r, "window_ms", o.restart.window, 100, 86400000);
  o.restart.stable_after = config::milliseconds(r, "stable_after_ms", o.restart.stable_after, 0, 86400000);
  const auto h = s.section("hold");
  // Comma-separated process names (Config reads scalars; a list of names reads as one).
  const std::string names = h.string("safety_critical", "lld,base_driver");
  o.safety_critical.clear();
  std::stringstream in(names);
  for (std::string n; std::getline(in, n, ',');) {
    n.erase(0, n.find_first_not_of(" \t"));
    n.erase(n.find_last_not_of(" \t") + 1);
    if (!n.empty()) o.safety_critical.push_back(n);
  }
  o.hold_hz = h.number("publish_hz", o.hold_hz, 1.0, 1000.0);
  o.hold_deadline = config::milliseconds(h, "deadline_ms", o.hold_deadline, 1, 10000);
  o.state_dir = s.string("state_dir", "");
  return o;
}

SupervisorChannels load_supervisor_channels(const config::Config& c)
{
  SupervisorChannels ch;
  config::read_strings(c, {{"heartbeat", &ch.heartbeat}, {"status", &ch.status}, {"orders", &ch.orders},
                           {"base_cmd", &ch.base_cmd}});
  return ch;
}

std::string default_state_dir()
{
  if (access("/run", W_OK) == 0) return "/run/rgnav";
  if (const char* xdg = std::getenv("XDG_RUNTIME_DIR"); xdg && *xdg) return std::string(xdg) + "/rgnav";
  return "/tmp/rgnav-" + std::to_string(getuid());
}

}  // namespace rgnav::supervisor
