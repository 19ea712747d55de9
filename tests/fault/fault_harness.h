// The fault-injection harness: launches a stack under a real supervisor and, for every
// process of the launch config, injects each fault and checks the supervisor's answer.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace rgnav::fault {

struct HarnessOptions
{
  std::string launch;             // launch config
  std::string host = "faulthost";
  std::string supervisor_bin;
  std::string supervisor_config;  // "" = the supervisor's default
  std::string order_key_file;     // the key orders to the supervisor are signed with
  std::string state_dir;          // supervisor state + probe state files
  std::string log_file;           // supervisor output
  std::string lcm_url;
  std::vector<std::string> processes;  // "" = all
  std::vector<std::string> faults;     // "" = all
  bool supervisor_fault = true;   // also SIGKILL and restart the supervisor (adoption)
  std::chrono::milliseconds heartbeat_timeout{500};
  std::chrono::milliseconds heartbeat_period{200};
  std::chrono::milliseconds restart_bound{3000};  // fault → heartbeating again
  int flood_messages = 3000;
  double flood_rate_hz = 2000;  // per input channel
  std::chrono::milliseconds stop_bound{200};  // fault -> commanded zero (plus braking for the measured)
  // The supervisor's bound on work without progress (its config's work_timeout_ms; a launch
  // command's own work_timeout_ms wins) and its stop-signal-to-SIGKILL grace: a busy loop is
  // detected within the first and running again after both plus a start.
  std::chrono::milliseconds work_timeout{1000};
  std::chrono::milliseconds hung_grace{300};
  // Busy loops are sent early in a step of work of the process's loop (its heartbeat shows a
  // turn under way for 100-300 ms), so that it takes the fault in only after that work: busy
  // and progressing until then, hung from then on.
  bool busy_loop_mid_work = false;
  // Drive-chain faults with the simulator's true motion to measure: how long to wait for the
  // robot to be moving before injecting (braking must be exercised).
  std::chrono::milliseconds moving_wait{45000};
  // Host stalls to inject before the process faults, one row each: every process of the stack
  // and the supervisor stopped together for this long while the robot drives (a loaded VM not
  // scheduling anyone), then continued. The drive chain must ride them out without stopping.
  std::vector<int> host_stall_ms;
};

struct FaultRow
{
  std::string process;
  std::string fault;
  std::optional<double> detect_ms;
  std::optional<double> hang_start_ms;     // busy loop: fault -> the process last seen progressing (its detection is bounded from there)
  std::optional<double> restart_ms;
  bool others_restarted = false;
  std::optional<bool> state_lost;
  std::optional<double> robot_stopped_ms;  // max of the two below
  std::optional<double> cmd_zero_ms;       // fault -> BASE_CMD zero (the supervisor's hold) and staying zero
  std::optional<double> drive_zero_ms;     // fault -> the drive's measured velocity at zero
  std::optional<double> drive_bound_ms;    // 200 ms + braking time from the velocity at the fault
  std::optional<double> brake_start_ms;    // fault -> the measured speed starts falling for good (<= 200 ms)
  std::optional<double> v_at_fault;        // [m/s] measured speed at the fault (moving: braking exercised)
  std::optional<double> omega_at_fault;    // [rad/s]
  std::optional<bool> stall_stop;          // host stall rows: the drives faulted or the robot came to rest
  std::optional<double> v_min_after;       // host stall rows: [m/s] lowest measured speed in the 2 s after
  std::optional<double> max_other_gap_ms;
  std::string status;  // pass, fail, pending
  std::string note;
};

const std::vector<std::string>& all_faults();

// Runs everything; rows in launch-config order.
std::vector<FaultRow> run_harness(const HarnessOptions& options);

}  // namespace rgnav::fault
