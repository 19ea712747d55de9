// What the fault harness sees on the bus: every HEARTBEAT (per process: newest pid, gaps
// between heartbeats, dropped-input counts), every SUPERVISOR_STATUS (a timeline of process
// states), the state counters probes publish, raw copies of each process's inputs (to
// flood them with), the drive chain (BASE_CMD, ODOMETRY, the simulator's true motion), and the stateful processes' published
// state (RG_MAP, ALIGNED_SCAN, the planner's GLOBAL_PATH, the explorer's EXPLORER_STATUS).
#pragma once

#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bus/drop_counter.h"
#include "bus/lcm_bus.h"
#include "rgnav/supervisor_status_t.hpp"

namespace rgnav::fault {

using Clock = std::chrono::steady_clock;

struct HeartbeatTrack
{
  int pid = 0;
  // When the newest heartbeat was sent (its utime, wall time on this host), and the largest gap
  // between sendings since reset_gaps(): whether the process beat, not when this observer got to
  // read it (during a flood its receive queue holds seconds of the flood ahead of them).
  Clock::time_point last{};
  std::chrono::milliseconds max_gap{0};
  std::chrono::milliseconds max_late{0}; // since reset_gaps(): the longest a heartbeat waited here to be read
  int64_t seq = -1;                      // the newest heartbeat's sequence number
  int64_t lost = 0;                      // since reset_gaps(): beats missing by sequence number (sent, never
                                         // heard here: lost on the bus or in this observer's receive queue)
  int64_t dropped = 0;                   // messages_dropped of the newest heartbeat
  int64_t messages_in = 0;               // accepted inputs of the newest heartbeat
  int32_t busy_ms = 0;                   // the newest heartbeat's time of its loop in the current turn
};

struct StatusSample
{
  Clock::time_point when;
  process_status_t p;
};

class BusObserver
{
 public:
  struct Channels
  {
    std::string base_cmd = "BASE_CMD";
    std::string drive_odometry = "ODOMETRY";
    std::string rg_map = "RG_MAP";
    std::string aligned_scan = "ALIGNED_SCAN";
    std::string global_path = "GLOBAL_PATH";   // the planner's goal and status
    std::string explorer_status = "EXPLORER_STATUS";   // the explorer's phase, stack and goals
    // The simulator's ground truth (odometry_t of the true motion) when the drives are emulated
    // inside it (protocol mode): the robot's real velocity, observable whichever process is
    // down. "" = none (the drive's own odometry is the only measure).
    std::string truth;
  };
  BusObserver(const std::string& url, const std::string& host, const std::vector<std::string>& input_channels,
              const std::map<std::string, std::string>& state_channels, const Channels& channels);

  // Dispatches messages for `d`.
  void spin(std::chrono::milliseconds d);
  // Spins until pred() or timeout; returns pred().
  bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout);

  bus::Bus& bus() { return bus_; }
  const HeartbeatTrack* heartbeat(const std::string& name) const;
  void reset_gaps();
  // Heartbeat gap of `name` (by the times they were sent) including the silence up to now.
  std::chrono::milliseconds gap_now(const std::string& name) const;
  // The longest any heartbeat waited in this observer's receive queue since reset_gaps().
  std::chrono::milliseconds max_late() const;

  std::optional<process_status_t> status(const std::string& name) const;
  const supervisor_status_t* last_status() const { return have_status_ ? &last_status_ : nullptr; }
  Clock::time_point last_status_time() const { return last_status_time_; }
  // First status sample of `name` at or after t that satisfies pred.
  std::optional<Clock::time_point> first_status(const std::string& name, Clock::time_point t,
                                                const std::function<bool(const process_status_t&)>& pred) const;
  // First heartbeat of `name` from a pid other than old_pid at or after t.
  std::optional<Clock::time_point> first_heartbeat_new_pid(const std::string& name, int old_pid, Clock::time_point t) const;
  // First heartbeat of `name`, pid `pid`, at or after t that counts accepted inputs (its live input began).
  std::optional<Clock::time_point> first_heartbeat_with_input(const std::string& name, int pid, Clock::time_point t) const;
  // The last heartbeat of `name`, pid `pid`, in [from, to] whose progress counter (loop turns,
  // handled inputs, steps of long work) differs from that of its last heartbeat in the window:
  // the process was last seen progressing then. None if every heartbeat of the window shows
  // the same count (no progress since before `from`).
  std::optional<Clock::time_point> last_seen_progressing(const std::string& name, int pid, Clock::time_point from,
                                                         Clock::time_point to) const;
  // The heartbeats of `name`, pid `pid`, in [from, to] for a row's note: "ms:+n" each, ms from
  // `t0` when it arrived, n the progress since the one before (so a late one, or progress that
  // came late, shows).
  std::string heartbeat_trace(const std::string& name, int pid, Clock::time_point from, Clock::time_point to,
                              Clock::time_point t0) const;

  // Newest state counter a probe published, and its first value at or after t.
  std::optional<int64_t> state(const std::string& name) const;
  std::optional<int64_t> first_state_since(const std::string& name, Clock::time_point t) const;

  const std::vector<uint8_t>* captured_input(const std::string& channel) const;
  // Off while the harness injects into inputs: it hears its own messages.
  void capture_inputs(bool on) { capture_inputs_ = on; }

  // Drive chain: every BASE_CMD (commanded) and every odometry of the drive under test
  // (measured, from base_driver), in arrival order, each stamped when it was made (its utime).
  struct VelocitySample
  {
    Clock::time_point when;
    double v = 0;
    double omega = 0;
    bool from_supervisor = false;  // the supervisor's hold
    int64_t deadline_us = 0;        // a command is void this long after it was sent
    bool fault = false;             // odometry: the base driver reports a drive fault (STATUS_FAULT)
    bool zero() const { return std::fabs(v) < 1e-3 && std::fabs(omega) < 1e-3; }
  };
  const std::vector<VelocitySample>& commands() const { return cmd_log_; }
  const std::vector<VelocitySample>& drive_odometry() const { return drive_log_; }
  // The robot's true velocity (Channels::truth), in arrival order; empty without a truth channel.
  const std::vector<VelocitySample>& truth() const { return truth_log_; }
  bool has_truth() const { return has_truth_; }

  // Stateful processes' published state: RG_MAP (rg_kernel) and ALIGNED_SCAN (scan_mapper).
  struct MapSample
  {
    Clock::time_point when;
    int64_t version = 0;
    int64_t last_scan_id = 0;
    std::vector<int64_t> region_ids;
    std::vector<int64_t> gateway_ids;
  };
  struct AlignedSample
  {
    Clock::time_point when;
    int64_t scan_id = 0;
    int32_t revision = 0;
  };
  // The planner's published goal state: GLOBAL_PATH (goal id, status).
  struct PathSample
  {
    Clock::time_point when;
    int64_t goal_id = 0;
    int8_t status = 0;
  };
  const std::vector<MapSample>& rg_maps() const { return map_log_; }
  const std::vector<AlignedSample>& aligned_scans() const { return aligned_log_; }
  const std::vector<PathSample>& paths() const { return path_log_; }
  // The explorer's published state: EXPLORER_STATUS (phase, gateway stack size, goals sent).
  struct ExplorerSample
  {
    Clock::time_point when;
    int8_t phase = 0;
    int64_t stack = 0;        // pending + done + set aside
    int64_t goals_sent = 0;
  };
  const std::vector<ExplorerSample>& explorer_states() const { return explorer_log_; }

 private:
  bus::LcmBus bus_;
  bus::DropCounter drops_;
  std::string host_;
  std::map<std::string, HeartbeatTrack> hb_;
  struct HeartbeatSample
  {
    Clock::time_point when;
    std::string name;
    int pid = 0;
    int64_t messages_in = 0;
    int64_t progress = 0;  // its progress counter
  };
  std::vector<HeartbeatSample> hb_log_;
  std::vector<StatusSample> status_log_;
  supervisor_status_t last_status_;
  bool have_status_ = false;
  Clock::time_point last_status_time_{};
  std::map<std::string, std::string> state_channel_of_;  // channel -> process
  std::map<std::string, std::vector<std::pair<Clock::time_point, int64_t>>> state_log_;
  std::map<std::string, std::vector<uint8_t>> inputs_;
  bool capture_inputs_ = true;
  std::vector<VelocitySample> cmd_log_;
  std::vector<VelocitySample> drive_log_;
  std::vector<VelocitySample> truth_log_;
  bool has_truth_ = false;
  std::vector<MapSample> map_log_;
  std::vector<AlignedSample> aligned_log_;
  std::vector<PathSample> path_log_;
  std::vector<ExplorerSample> explorer_log_;
};

}  // namespace rgnav::fault
