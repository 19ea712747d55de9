// Options of the supervisor (config/supervisor.yaml, section `supervisor`), loaded and
// validated outside the Supervisor and held const inside it.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "config/config.h"
#include "restart_policy.h"

namespace rgnav::supervisor {

struct SupervisorOptions
{
  std::chrono::milliseconds heartbeat_timeout{500};   // hung when heartbeats stop this long
  std::chrono::milliseconds startup_timeout{5000};    // to the first heartbeat after start
  std::chrono::milliseconds work_timeout{1000};       // hung when heartbeats come but progress stands still this long
  // ... unless its loop is waiting on the disk (main thread in state D): that is slow, not
  // stuck, and is allowed this much longer.
  std::chrono::milliseconds disk_wait_timeout{10000};
  // A gap in the supervisor's own tick this much longer than the tick is a stall of the
  // whole host: its length is added to every process's deadlines.
  std::chrono::milliseconds stall_threshold{50};
  // A stall the supervisor did not feel (the processes starved while it ran, the bus late):
  // heartbeats of several processes silent past the bound whose newest beats lie within
  // stall_window of each other began their silence together; the verdict is held up to
  // stall_hold longer, and one still silent then is hung (shared_silence.h). The window must be
  // wider than a heartbeat period (5 Hz: 200 ms) and is at most half of heartbeat_timeout; the
  // longest silence a hang can hide in is heartbeat_timeout + stall_hold (issue 35: <= 1 s).
  // stall_window 0 or stall_hold 0: every silence past its bound is a hang, as before.
  std::chrono::milliseconds stall_window{250};
  std::chrono::milliseconds stall_hold{300};
  std::chrono::milliseconds hung_grace{300};          // stop signal → SIGKILL for a hung process
  std::chrono::milliseconds tick{10};                 // exit reaping and timeout checks
  std::chrono::milliseconds status_period{1000};      // SUPERVISOR_STATUS
  std::chrono::milliseconds status_min_gap{50};       // extra status on changes, at most this often
  std::chrono::milliseconds remote_fresh{2000};       // a remote dependency counts as up this long after its heartbeat
  std::chrono::milliseconds orphan_grace{5000};       // stopping strangers from an old state file
  bool default_auto_respawn = true;
  RestartOptions restart;
  std::vector<std::string> safety_critical{"lld", "base_driver"};
  double hold_hz = 50.0;                              // zero BASE_CMD while the robot is held
  std::chrono::milliseconds hold_deadline{100};
  std::string state_dir;                              // "" = default_state_dir()
};

struct SupervisorChannels
{
  std::string heartbeat = "HEARTBEAT";
  std::string status = "SUPERVISOR_STATUS";
  std::string orders = "SUPERVISOR_ORDERS";
  std::string base_cmd = "BASE_CMD";
};

SupervisorOptions load_supervisor_options(const config::Config& section);
SupervisorChannels load_supervisor_channels(const config::Config& section);

// /run/rgnav if writable, else $XDG_RUNTIME_DIR/rgnav, else /tmp/rgnav-<uid>.
std::string default_state_dir();

}  // namespace rgnav::supervisor
