// The deputy's logic: which local processes should run, starting them in dependency order,
// watching each two ways (exit via waitpid, liveness via HEARTBEAT), stopping them with
// their signal then SIGKILL, restarting with back-off and an intensity limit, holding the
// robot when a safety-critical process is given up, and adopting the children of a previous
// supervisor instance. No LCM in here: the node adapter feeds heartbeats and orders in and
// publishes status() and the hold.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "launch_plan.h"
#include "proc_info.h"
#include "restart_policy.h"
#include "shared_silence.h"
#include "supervisor_options.h"

namespace rgnav::supervisor {

// Same values as process_status_t::STATE_*.
enum class ProcState : int8_t { kStopped = 0, kStarting = 1, kRunning = 2, kHung = 3, kBackoff = 4, kFailed = 5, kStopping = 6 };
const char* to_string(ProcState s);

enum class Order : int8_t { kStart = 1, kStop = 2, kRestart = 3, kShutdown = 4 };

struct ProcessView
{
  std::string name;
  std::string group;
  ProcState state = ProcState::kStopped;
  pid_t pid = 0;
  int restarts = 0;
  std::string last_exit;
  int64_t heartbeat_age_us = -1;
  float cpu_percent = 0;
  int64_t rss_kb = 0;
  bool adopted = false;
};

class Supervisor
{
 public:
  using Clock = std::chrono::steady_clock;

  // Only commands whose host is `host` (or unset) are supervised here. state_dir holds the
  // state file and the per-process lock files (created if needed).
  Supervisor(LaunchPlan plan, std::string host, SupervisorOptions options, std::string state_dir);
  ~Supervisor() = default;
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // Finds children a previous instance left running: adopts those still in the plan,
  // stops the others. Call once, before start_all().
  void recover(Clock::time_point now);
  // Wants every local command running (the launch).
  void start_all(Clock::time_point now);
  // Start/stop/restart a command or group ("" or "everything": all), or shut down.
  // False (with why) if the target is unknown here.
  bool order(Order order, const std::string& target, Clock::time_point now, std::string* why);
  void shutdown(Clock::time_point now);
  bool shutting_down() const { return shutting_down_; }
  // After shutdown(): every child has exited.
  bool finished() const;

  // A heartbeat from this machine (same_machine) is matched to a child by its pid, whatever
  // name the process gives itself; its name alone also counts as a (remote) dependency's.
  // progress: the heartbeat's work counter (0 until the process's loop first turns); standing
  // still longer than the command's work_timeout while heartbeats go on is a hang, and so is
  // still 0 after startup_timeout. seq: the heartbeat's sequence number (-1: unknown); a jump
  // counts heartbeats lost on the way (heartbeats_lost()).
  void on_heartbeat(const std::string& name, pid_t pid, Clock::time_point now, bool same_machine = true,
                    int64_t progress = 0, int64_t seq = -1);
  // The supervisor's own schedule was `gap` late (the host stalled, everyone with it): no
  // process is blamed for it. The node measures the gap; counted in host_stalls().
  // Stalls it did not feel show as heartbeats of several processes stopping together: those
  // are held, not judged, and counted there too (shared_silence.h).
  void on_host_stall(Clock::duration gap, Clock::time_point now);
  struct HostStalls
  {
    int count = 0;
    std::chrono::milliseconds longest{0};
    std::chrono::milliseconds total{0};
    int heard = 0;       // of count: shared silences of heartbeats (not felt in the supervisor's tick)
    int heard_lost = 0;  // of heard: the first one back had sent heartbeats that were lost (its seq jumped)
  };
  const HostStalls& host_stalls() const { return stalls_; }
  // Heartbeats of our processes sent but never received (gaps in their sequence numbers).
  int64_t heartbeats_lost() const { return heartbeats_lost_; }
  void on_child_exit(pid_t pid, int wait_status, Clock::time_point now);
  // Reaps exited children (waitpid, non-blocking).
  void reap(Clock::time_point now);
  // Timeouts, back-off, dependencies, kill deadlines, adopted children's liveness.
  void tick(Clock::time_point now);

  std::vector<ProcessView> status(Clock::time_point now);
  // Held (zero BASE_CMD) while a safety-critical process is down after a crash or hang, until
  // it runs again, and latched while one is FAILED.
  bool robot_held() const;
  const std::string& alert() const { return alert_; }
  // New alerts since the previous call (for logging).
  std::vector<std::string> take_alerts();
  // An alert from the node (a refused order): logged, and the status's alert.
  void note_alert(const std::string& text) { raise_alert(text); }
  // True once after any state change (publish status promptly).
  bool take_changed();

  const std::string& host() const { return host_; }
  const LaunchPlan& plan() const { return plan_; }
  std::string state_path() const { return state_dir_ + "/supervisor.json"; }
  std::string lock_path(const std::string& name) const { return state_dir_ + "/" + name + ".lock"; }
  // How a process's main thread state is read (proc_info.h's main_thread_state; tests stand in).
  void set_thread_state_reader(std::function<char(pid_t)> read) { thread_state_ = std::move(read); }

 private:
  enum class StopIntent { kNone, kOperator, kRestart, kHung, kShutdown };

  struct Entry
  {
    const PlannedCommand* cmd = nullptr;
    bool missing = false;
    bool safety_critical = false;
    bool auto_respawn = true;
    std::chrono::milliseconds heartbeat_timeout{500};
    std::chrono::milliseconds startup_timeout{5000};
    std::chrono::milliseconds work_timeout{1000};
    ProcState state = ProcState::kStopped;
    bool want_running = false;
    pid_t pid = 0;
    uint64_t start_ticks = 0;
    bool adopted = false;
    Clock::time_point started{};
    std::optional<Clock::time_point> last_heartbeat;
    int64_t progress = -1;           // the newest heartbeat's work counter (-1: none yet)
    Clock::time_point progress_at{};  // when it last moved on
    bool silence_held = false;        // silent past its bound together with others: verdict held
    int64_t seq = -1;                 // the newest heartbeat's sequence number (-1: none yet)
    std::optional<Clock::time_point> disk_wait_seen;   // its main thread last seen in a disk wait, since then
    StopIntent intent = StopIntent::kNone;
    Clock::time_point kill_at{};
    bool killed = false;
    Clock::time_point restart_at{};
    int restarts = 0;
    std::string last_exit;
    std::string hung_reason;
    bool done = false;           // a oneshot that exited 0
    bool down_unplanned = false;  // crashed or hung, not running again yet
    bool name_warned = false;
    RestartPolicy policy;
    explicit Entry(const RestartOptions& r) : policy(r) {}
  };

  struct Orphan
  {
    std::string name;
    pid_t pid = 0;
    uint64_t start_ticks = 0;
    Clock::time_point kill_at{};
    bool killed = false;
  };

  Entry* find(const std::string& name);
  Entry* find_pid(pid_t pid);
  std::vector<Entry*> targets(const std::string& target);
  bool dependencies_up(const Entry& e, Clock::time_point now) const;
  bool dependents_alive(const Entry& e) const;
  void spawn(Entry& e, Clock::time_point now);
  void adopt(Entry& e, pid_t pid, uint64_t start_ticks, Clock::time_point now);
  void begin_stop(Entry& e, StopIntent intent, Clock::time_point now);
  void exited(Entry& e, const std::string& how, Clock::time_point now);
  void failure(Entry& e, const std::string& reason, Clock::time_point now);
  void set_state(Entry& e, ProcState s);
  void running_again(Entry& e);
  void raise_alert(const std::string& text);
  // Its heartbeats have been silent past its bound: hung, or held while others' silences
  // began together with its own (shared_silence.h).
  void judge_silence(Entry& e, Clock::time_point now);
  void release_silence(Entry& e);
  void count_stall(Clock::duration length);
  // Its loop stands still in a disk wait (slow, not stuck), within disk_wait_timeout: in one now,
  // or seen in one within its work bound (a loop writing to a loaded disk leaves the wait for a
  // moment between writes: sampled then, it was taken for hung).
  bool waiting_on_disk(Entry& e, Clock::time_point now);
  void save();

  LaunchPlan plan_;
  std::string host_;
  const SupervisorOptions options_;
  std::string state_dir_;
  std::vector<Entry> entries_;  // local commands, in start order
  std::vector<Orphan> orphans_;
  std::vector<std::pair<std::string, Clock::time_point>> seen_;  // newest heartbeat per name
  bool shutting_down_ = false;
  bool held_ = false;
  bool changed_ = true;
  std::string alert_;
  std::vector<std::string> new_alerts_;
  Clock::time_point last_adopted_check_{};
  CpuMeter cpu_;
  HostStalls stalls_;
  SharedSilence silence_;
  int64_t heartbeats_lost_ = 0;
  std::function<char(pid_t)> thread_state_ = main_thread_state;
};

}  // namespace rgnav::supervisor
