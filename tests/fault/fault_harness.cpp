#include "fault_harness.h"

#include <dirent.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <random>
#include <set>
#include <thread>
#include <spdlog/spdlog.h>

#include "bus/typed.h"
#include "bus_observer.h"
#include "child_process.h"
#include "launch_parser.h"
#include "launch_plan.h"
#include "order_auth.h"
#include "order_conversions.h"
#include "proc_info.h"
#include "recording.h"
#include "rgnav/explorer_status_t.hpp"
#include "rgnav/fault_inject_t.hpp"
#include "rgnav/global_path_t.hpp"
#include "rgnav/supervisor_order_t.hpp"
#include "runtime/fault_injection.h"
#include "time/message_time.h"

namespace rgnav::fault {

namespace sup = rgnav::supervisor;

const std::vector<std::string>& all_faults()
{
  static const std::vector<std::string> f = {"sigkill", "sigstop", "busy_loop", "crash_loop", "flood", "malformed", "loss_dup_delay"};
  return f;
}

namespace {

const std::set<std::string> kDriveChain = {"lld", "base_driver", "collision_avoidance"};
// Added to a braking time: the commander's period (a ramp goes down in steps) and the sampling
// of the measured speed.
constexpr double kBrakeSlackMs = 50.0;

double ms_between(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string arg_after(const std::vector<std::string>& argv, const std::string& flag)
{
  for (size_t i = 0; i + 1 < argv.size(); ++i)
    if (argv[i] == flag) return argv[i + 1];
  return "";
}

int count_instances(const std::vector<std::string>& argv)
{
  int n = 0;
  DIR* d = opendir("/proc");
  if (!d) return -1;
  while (dirent* e = readdir(d)) {
    const int pid = std::atoi(e->d_name);
    if (pid <= 0) continue;
    const auto st = sup::read_proc_stat(pid);
    if (st && st->state != 'Z' && sup::read_cmdline(pid) == argv) ++n;
  }
  closedir(d);
  return n;
}

class Harness
{
 public:
  explicit Harness(const HarnessOptions& o) : o_(o) {}

  std::vector<FaultRow> run()
  {
    const char* root = std::getenv("RGNAV_ROOT");
    const char* build = std::getenv("RGNAV_BUILD");
    // The supervisor's run folder for this host: exec lines may name files in it.
    setenv("RGNAV_RUN_DIR", (o_.state_dir + "/" + o_.host).c_str(), 1);
    // The stack's processes (the supervisor's children inherit it) take faults on FAULT_INJECT.
    setenv(runtime::kFaultInjectionEnv, "1", 1);
    sup::PlanOptions po{root ? root : "", build ? std::string(build) + "/bin" : "", true};
    plan_ = sup::make_plan(sup::parse_launch_file(o_.launch), po);
    std::vector<std::string> inputs;
    std::map<std::string, std::string> state_channels;
    for (const auto& c : plan_.commands) {
      if (!c.spec.host.empty() && c.spec.host != o_.host) continue;
      local_.push_back(&c);
      for (const auto& i : c.spec.inputs) inputs.push_back(i);
      const auto out = arg_after(c.argv, "--output");
      if (!out.empty() && !arg_after(c.argv, "--state").empty()) state_channels[c.spec.name] = out;
    }
    BusObserver::Channels channels;
    for (const auto* c : local_) learn_role(*c, channels);
    obs_ = std::make_unique<BusObserver>(o_.lcm_url, o_.host, inputs, state_channels, channels);
    // A process whose dependency is not built never starts: it is pending too.
    for (bool grew = true; grew;) {
      grew = false;
      for (const auto* c : local_) {
        if (c->executable.empty() || blocked_.count(c->spec.name)) continue;
        for (const auto& d : c->spec.depends) {
          const auto* dep = plan_.find(d);
          if (dep && (dep->executable.empty() || blocked_.count(d))) {
            blocked_[c->spec.name] = d;
            grew = true;
          }
        }
      }
    }

    std::vector<FaultRow> rows;
    const auto faults = o_.faults.empty() ? all_faults() : o_.faults;
    std::ofstream(o_.log_file, std::ios::trunc);  // the log is read back (checkpoint reports)
    start_supervisor();
    if (!wait_all_running(std::chrono::seconds(30))) {
      // Report every process rather than nothing: the ones that are built failed to come up.
      for (const auto* c : local_) {
        FaultRow row;
        row.process = c->spec.name;
        row.fault = "startup";
        const auto s = obs_->status(c->spec.name);
        row.status = c->executable.empty() || blocked_.count(c->spec.name) ? "pending" : "fail";
        row.note = row.status == "pending" ? "not built (or a dependency is not)"
                                           : std::string("stack did not come up within 30 s; state ") +
                                                 (s ? std::to_string(s->state) + " " + s->last_exit : "unknown") + " (see " + o_.log_file + ")";
        rows.push_back(row);
      }
      stop_supervisor();
      return rows;
    }
    if (!mapper_proc_.empty()) {
      if (const auto n = reloaded(0, mapper_proc_)) mapper_base_ = *n;
      mapper_instance_start_ = sup_started_;
    }
    if (!rg_map_proc_.empty())
      if (const auto n = reloaded(0, rg_map_proc_)) rg_base_ = *n;
    // Normal jitter of every heartbeat, for the "others undisturbed" check.
    obs_->reset_gaps();
    obs_->spin(std::chrono::milliseconds(2000));
    for (const auto* c : running_commands()) baseline_gap_[c->spec.name] = obs_->gap_now(c->spec.name);

    // Host stalls first, on the fresh stack (a robot that later faults left stuck cannot show
    // whether a stall stops it).
    for (const int ms : o_.host_stall_ms) {
      rows.push_back(host_stall(std::chrono::milliseconds(ms)));
      const auto& r = rows.back();
      spdlog::info("{:<16} {:<15} {:<7} {}", r.process, r.fault, r.status, r.note);
    }
    for (const auto* c : local_) {
      // Every process is watched; only the selected ones get faults.
      if (!o_.processes.empty() && std::find(o_.processes.begin(), o_.processes.end(), c->spec.name) == o_.processes.end()) continue;
      for (const auto& f : faults) {
        FaultRow row;
        row.process = c->spec.name;
        row.fault = f;
        if (c->executable.empty() || blocked_.count(c->spec.name)) {
          row.status = "pending";
          row.note = c->executable.empty() ? "process not built yet (" + c->argv[0] + ")"
                                           : "depends on " + blocked_.at(c->spec.name) + ", which is not built yet";
        } else {
          run_fault(*c, f, row);
          if (!wait_all_running(std::chrono::seconds(15))) row.note += "; stack not back to running after the fault";
          obs_->spin(std::chrono::milliseconds(300));
        }
        spdlog::info("{:<16} {:<15} {:<7} detect={} restart={} {}", row.process, row.fault, row.status,
                     row.detect_ms ? std::to_string(static_cast<int>(*row.detect_ms)) : "-",
                     row.restart_ms ? std::to_string(static_cast<int>(*row.restart_ms)) : "-", row.note);
        rows.push_back(row);
      }
    }
    if (o_.supervisor_fault && running_commands().empty()) {
      FaultRow row;
      row.process = "supervisor";
      row.fault = "sigkill_adopt";
      row.status = "pending";
      row.note = "no process of this launch config is built: nothing to adopt";
      rows.push_back(row);
    } else if (o_.supervisor_fault) {
      rows.push_back(supervisor_fault());
      const auto& r = rows.back();
      spdlog::info("{:<16} {:<15} {:<7} detect={} restart={} {}", r.process, r.fault, r.status,
                   r.detect_ms ? std::to_string(static_cast<int>(*r.detect_ms)) : "-",
                   r.restart_ms ? std::to_string(static_cast<int>(*r.restart_ms)) : "-", r.note);
    }
    stop_supervisor();
    return rows;
  }

  ~Harness()
  {
    if (sup_pid_ > 0) stop_supervisor();
  }

 private:
  // What a process is, from its real config: the RG map keeper (persistence.state_dir +
  // channels.rg_map), the scan mapper (persistence.state_file + channels.aligned_scan), the
  // base driver (drives.*), the planner (channels.nav_goal + channels.global_path +
  // channels.targets, and a --state-file), the explorer (channels.region_name_request +
  // channels.status, and a --state-file), so the checks follow the configs rather than names.
  void learn_role(const sup::PlannedCommand& c, BusObserver::Channels& channels)
  {
    const std::string path = arg_after(c.argv, "--config");
    if (path.empty() || c.executable.empty()) return;
    YAML::Node y;
    try {
      y = YAML::LoadFile(path);
    } catch (const std::exception&) {
      return;
    }
    const auto str = [&](const char* a, const char* b) -> std::string {
      const auto sa = y[a];
      if (!sa || !sa.IsMap()) return "";
      const auto v = sa[b];
      return v && v.IsScalar() ? v.as<std::string>() : "";
    };
    if (!str("persistence", "state_dir").empty() && !str("channels", "rg_map").empty()) {
      rg_map_proc_ = c.spec.name;
      channels.rg_map = str("channels", "rg_map");
    }
    if (!str("persistence", "state_file").empty() && !str("channels", "aligned_scan").empty()) {
      mapper_proc_ = c.spec.name;
      channels.aligned_scan = str("channels", "aligned_scan");
    }
    const auto drives = y["drives"];
    if (drives && drives.IsMap() && drives["translation"] && !str("channels", "odometry").empty()) {
      base_proc_ = c.spec.name;
      channels.drive_odometry = str("channels", "odometry");
      decel_v_ = drives["translation"]["max_acceleration"] ? drives["translation"]["max_acceleration"].as<double>() : 1.0;
      decel_w_ = drives["rotation"] && drives["rotation"]["max_acceleration"] ? drives["rotation"]["max_acceleration"].as<double>() : 1.0;
    }
    const auto chs = y["channels"];
    if (chs && chs.IsMap() && chs["base_cmd"]) channels.base_cmd = "BASE_CMD";  // the hold's channel
    // The simulator in protocol mode (sim + drive sections, a truth channel): the drives are its
    // emulated CiA 402 drives, its truth is the robot's real motion, observable whichever process
    // is down, and its body brakes no faster than its own braking limit (drive.brake_decel; an
    // older config without one brakes at its acceleration).
    const auto sim = y["sim"], body = y["drive"];
    if (sim && sim.IsMap() && body && body.IsMap() && !str("channels", "truth").empty()) {
      const std::string flag = arg_after(c.argv, "--interface");
      if ((flag.empty() ? str("sim", "interface") : flag) == "protocol") {
        channels.truth = str("channels", "truth");
        if (body["brake_decel"]) sim_brake_decel_ = body["brake_decel"].as<double>();
        else if (body["accel"]) sim_brake_decel_ = body["accel"].as<double>();
        if (body["alpha"]) sim_alpha_ = body["alpha"].as<double>();
      }
    }
    // The lld (a trajectory in, commands out, a control loop): its controlled stop brakes at
    // max(limits.stop_decel_mps2, the robot's max acceleration), turns at the robot's max angular
    // acceleration, and it follows a trajectory nobody re-sends for timeouts.trajectory_s.
    if (!str("channels", "trajectory").empty() && !str("channels", "command").empty() && y["loop"] && y["timeouts"]) {
      lld_proc_ = c.spec.name;
      double a = y["limits"] && y["limits"]["stop_decel_mps2"] ? y["limits"]["stop_decel_mps2"].as<double>() : 0.0;
      const char* root = std::getenv("RGNAV_ROOT");
      try {
        const YAML::Node d = YAML::LoadFile(std::string(root ? root : ".") + "/config/robot.yaml")["robot"]["drive"];
        if (d && d["max_accel_mps2"]) a = std::max(a, d["max_accel_mps2"].as<double>());
        if (d && d["max_alpha_radps2"]) lld_decel_w_ = d["max_alpha_radps2"].as<double>();
      } catch (const std::exception&) {
      }
      if (a > 0) lld_decel_v_ = a;
      if (y["timeouts"]["trajectory_s"]) lld_trajectory_timeout_s_ = y["timeouts"]["trajectory_s"].as<double>();
    }
    // Collision avoidance: targets in, trajectories out.
    if (!str("channels", "targets").empty() && !str("channels", "trajectory").empty() && y["planner"]) ca_proc_ = c.spec.name;
    // The planner: goals in, their state and targets out, kept across restarts with --state-file.
    if (!str("channels", "nav_goal").empty() && !str("channels", "global_path").empty() &&
        !str("channels", "targets").empty() && !arg_after(c.argv, "--state-file").empty()) {
      planner_proc_ = c.spec.name;
      channels.global_path = str("channels", "global_path");
    }
    // The explorer: its gateway stack and goal counter kept across restarts with --state-file.
    if (!str("channels", "region_name_request").empty() && !str("channels", "status").empty() &&
        !arg_after(c.argv, "--state-file").empty()) {
      explorer_proc_ = c.spec.name;
      channels.explorer_status = str("channels", "status");
    }
  }

  // A oneshot job that finished (exit 0) is done, not down.
  bool done(const std::string& name) const
  {
    const auto s = obs_->status(name);
    return s && s->state == process_status_t::STATE_STOPPED && s->last_exit.rfind("done", 0) == 0;
  }

  std::vector<const sup::PlannedCommand*> running_commands() const
  {
    std::vector<const sup::PlannedCommand*> out;
    for (const auto* c : local_)
      if (!c->executable.empty() && !blocked_.count(c->spec.name) && !done(c->spec.name)) out.push_back(c);
    return out;
  }

  void start_supervisor()
  {
    std::vector<std::string> argv = {o_.supervisor_bin, "--launch", o_.launch, "--host", o_.host, "--state-dir", o_.state_dir,
                                     "--skip-missing"};
    if (!o_.supervisor_config.empty()) {
      argv.push_back("--config");
      argv.push_back(o_.supervisor_config);
    }
    if (!o_.lcm_url.empty()) {
      argv.push_back("--lcm-url");
      argv.push_back(o_.lcm_url);
    }
    std::string line = "exec";
    for (const auto& a : argv) line += " '" + a + "'";
    line += " >>'" + o_.log_file + "' 2>&1";
    const auto r = sup::spawn_child({"/bin/sh", {"sh", "-c", line}, {}, ""});
    if (r.pid == 0) throw std::runtime_error("cannot start supervisor: " + r.error);
    sup_pid_ = r.pid;
    sup_started_ = Clock::now();
  }

  void stop_supervisor()
  {
    if (sup_pid_ <= 0) return;
    kill(sup_pid_, SIGTERM);
    for (int i = 0; i < 300; ++i) {
      obs_->spin(std::chrono::milliseconds(100));
      int status = 0;
      if (waitpid(sup_pid_, &status, WNOHANG) == sup_pid_) {
        sup_pid_ = 0;
        return;
      }
    }
    kill(sup_pid_, SIGKILL);
    waitpid(sup_pid_, nullptr, 0);
    sup_pid_ = 0;
  }

  bool all_running() const
  {
    if (obs_->last_status_time() < sup_started_) return false;
    for (const auto* c : running_commands()) {
      const auto s = obs_->status(c->spec.name);
      if (!s || s->state != process_status_t::STATE_RUNNING) return false;
      if (c->spec.heartbeat) {
        const auto* hb = obs_->heartbeat(c->spec.name);
        if (!hb || hb->pid != s->pid) return false;
      }
    }
    return true;
  }

  bool wait_all_running(std::chrono::milliseconds timeout)
  {
    return obs_->wait_until([this] { return all_running(); }, timeout);
  }

  std::map<std::string, std::pair<int, int>> snapshot() const
  {
    std::map<std::string, std::pair<int, int>> s;
    for (const auto* c : running_commands())
      if (const auto p = obs_->status(c->spec.name)) s[c->spec.name] = {p->pid, p->restarts};
    return s;
  }

  // ", N lost on the way" when heartbeats of `name` were sent but never heard (their sequence
  // numbers skip): the process beat, the bus or this observer's receive queue lost them.
  std::string lost_on_the_way(const std::string& name) const
  {
    const auto* t = obs_->heartbeat(name);
    return t && t->lost > 0 ? ", " + std::to_string(t->lost) + " lost on the way" : "";
  }

  // Others restarted, and the largest heartbeat gap among them beyond their normal jitter.
  void check_others(const std::string& self, const std::map<std::string, std::pair<int, int>>& before, FaultRow& row)
  {
    double worst = 0;
    std::string jittery;
    for (const auto* c : running_commands()) {
      const auto& n = c->spec.name;
      if (n == self) continue;
      const auto p = obs_->status(n);
      if (!p || before.count(n) == 0 || p->pid != before.at(n).first || p->restarts != before.at(n).second) {
        row.others_restarted = true;
        row.note += "; " + n + " restarted";
      }
      if (!c->spec.heartbeat) continue;
      const double gap = static_cast<double>(obs_->gap_now(n).count());
      worst = std::max(worst, gap);
      // Normal jitter: the gap seen in the quiet baseline, doubled, with a floor for a loaded machine.
      const double base = static_cast<double>(baseline_gap_[n].count());
      // Disturbed = came near being declared hung; below that, a loaded machine's scheduling.
      const double bound = std::max(2.0 * base, static_cast<double>(o_.heartbeat_timeout.count()));
      if (gap > bound)
        jittery += " " + n + "(" + std::to_string(static_cast<int>(gap)) + ">" + std::to_string(static_cast<int>(bound)) + "ms" +
                   lost_on_the_way(n) + ")";
    }
    row.max_other_gap_ms = worst;
    if (!jittery.empty()) row.note += "; heartbeat gap beyond jitter:" + jittery;
    gaps_ok_ = jittery.empty();
  }

  bool is_drive_row(const sup::PlannedCommand& c) const { return c.spec.safety_critical || kDriveChain.count(c.spec.name) > 0; }

  // Waits until the robot moves (the simulator's truth: >= 0.15 m/s, or >= 0.3 rad/s turning).
  bool wait_moving(std::chrono::milliseconds timeout)
  {
    return obs_->wait_until([&] {
      const auto& t = obs_->truth();
      if (t.empty() || Clock::now() - t.back().when > std::chrono::milliseconds(100)) return false;
      return std::fabs(t.back().v) >= 0.15 || std::fabs(t.back().omega) >= 0.3;
    }, timeout);
  }

  // Decelerations the robot can be expected to brake at: the slowest stop of the chain (the
  // base driver's ramps, the lld's controlled stop) and never faster than the simulated body.
  double stop_decel_v() const
  {
    double a = decel_v_;
    if (lld_decel_v_ > 0) a = std::min(a, lld_decel_v_);
    if (sim_brake_decel_ > 0) a = std::min(a, sim_brake_decel_);
    return a;
  }
  double stop_decel_w() const
  {
    double a = decel_w_;
    if (lld_decel_w_ > 0) a = std::min(a, lld_decel_w_);
    if (sim_alpha_ > 0) a = std::min(a, sim_alpha_);
    return a;
  }

  // When the measured speed started falling for good before sample k: walking back from k over
  // samples no faster than the one before, in v, or in omega for a robot turning in place
  // (`rotation`). A ramp commanded in steps holds its speed between them, so up to kFlatSamples
  // equal samples in a row belong to the fall; more are a cruise. Returns the first slower
  // sample of the earliest fall (late by up to one sample period: conservative).
  static std::optional<Clock::time_point> brake_onset(const std::vector<BusObserver::VelocitySample>& s, size_t k,
                                                      Clock::time_point from, bool rotation)
  {
    constexpr int kFlatSamples = 3;
    std::optional<size_t> first_fall;
    int flat = 0;
    for (size_t j = k; j > 0 && s[j - 1].when >= from; --j) {
      const double d = rotation ? std::fabs(s[j].omega) - std::fabs(s[j - 1].omega) : std::fabs(s[j].v) - std::fabs(s[j - 1].v);
      if (d < -1e-3) {
        first_fall = j;
        flat = 0;
      } else if (d > 1e-3 || ++flat > kFlatSamples) {
        break;
      }
    }
    if (!first_fall) return std::nullopt;
    return s[*first_fall].when;
  }

  // The drive chain after a fault of one of its processes: the commanded velocity (BASE_CMD:
  // the dead commander's last command expiring, or the supervisor's hold) at zero within
  // stop_bound, and the measured velocity at zero within stop_bound plus the braking time from
  // the velocity at the fault at the chain's slowest stop deceleration; with the simulator's
  // truth, also the moment braking began (<= stop_bound). Measured: the simulator's true motion
  // where the drives are emulated inside it (observable while the base driver is down), else
  // the base driver's odometry. Collision avoidance's bound starts when the lld gives up the
  // trajectory it no longer re-sends. `back`: when the process was running again (the window
  // ends there).
  void measure_drive(const sup::PlannedCommand& c, Clock::time_point t0, std::optional<Clock::time_point> back, FaultRow& row)
  {
    if (!is_drive_row(c)) return;
    const auto end = back ? *back : t0 + o_.restart_bound;
    obs_->wait_until([&] { return Clock::now() >= end + std::chrono::milliseconds(100); },
                     std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()) + std::chrono::seconds(1));
    const bool consumer = c.spec.name == base_proc_;
    const bool truth = obs_->has_truth();
    const double stop_bound = static_cast<double>(o_.stop_bound.count()) +
                              (c.spec.name == ca_proc_ ? 1000.0 * lld_trajectory_timeout_s_ : 0.0);
    const auto& cmds = obs_->commands();
    const auto& odo = truth ? obs_->truth() : obs_->drive_odometry();
    const BusObserver::VelocitySample* at_fault = nullptr;
    for (const auto& m : odo)
      if (m.when < t0) at_fault = &m;
    // Braking time from the speed at the fault (measured; else commanded) at the slowest stop.
    double v0 = 0, w0 = 0;
    if (at_fault) {
      v0 = std::fabs(at_fault->v);
      w0 = std::fabs(at_fault->omega);
    } else if (const VelocitySampleRef last = last_nonzero(cmds, t0 - std::chrono::seconds(1), t0); last.sample) {
      v0 = std::fabs(last.sample->v);
      w0 = std::fabs(last.sample->omega);
    }
    // Braking time at the slowest stop, from the speed when braking began (a commander driving
    // blind until its input goes stale may still speed up within the stop bound), plus the
    // command period and the truth's sampling.
    double brake_ms = 1000.0 * std::max(v0 / stop_decel_v(), w0 / stop_decel_w()) + kBrakeSlackMs;

    // Commanded velocity.
    std::optional<Clock::time_point> cmd_zero;
    int nonzero_after = 0;
    if (consumer) {
      // Nobody listens to BASE_CMD while the base driver is down; the supervisor's hold is
      // what it finds when it returns. Other commanders keep going (their business).
      for (const auto& m : cmds)
        if (m.when >= t0 && m.from_supervisor && m.zero()) {
          cmd_zero = m.when;
          break;
        }
    } else {
      // The effective command: the newest unexpired one. Zero from the moment the last
      // non-zero one expires or is replaced by a zero (the hold) until `end`.
      const VelocitySampleRef last = last_nonzero(cmds, t0 - std::chrono::seconds(2), end);
      if (!last.sample) {
        cmd_zero = t0;
      } else {
        Clock::time_point t = last.sample->when + std::chrono::microseconds(last.sample->deadline_us);
        for (size_t i = last.index + 1; i < cmds.size() && cmds[i].when < t; ++i)
          if (cmds[i].zero()) {
            t = cmds[i].when;
            break;
          }
        if (last.sample->when >= t0) ++nonzero_after;
        cmd_zero = std::max(t, t0);
      }
    }
    if (cmd_zero) row.cmd_zero_ms = ms_between(t0, *cmd_zero);
    else row.note += "; BASE_CMD never zero (no hold)";
    // A commander still alive after the fault (its own input went stale) brakes by a ramp of
    // non-zero commands: zero after the braking time. (A hung one let run again to stop may send
    // one more: what it does to the robot is measured below.)
    if (nonzero_after > 0) row.note += "; non-zero BASE_CMD after the fault";
    bool ok = cmd_zero.has_value();

    // Measured velocity.
    if ((base_proc_.empty() && !truth) || !at_fault) {
      row.note += "; no drive odometry to measure";
    } else if (consumer && !truth) {
      // Unobservable while the base driver itself is down (the drives quick-stop on the lost
      // master heartbeat): its successor's first report must be standstill.
      const BusObserver::VelocitySample* first = nullptr;
      obs_->wait_until([&] {
        for (const auto& m : obs_->drive_odometry())
          if (m.when >= end) return (first = &m) != nullptr;
        return false;
      }, std::chrono::seconds(3));
      if (!first) {
        ok = false;
        row.note += "; no odometry from the restarted base driver";
      } else {
        if (first->zero()) {
          row.drive_zero_ms = ms_between(t0, first->when);
          row.note += "; drives at rest when the base driver came back";
        } else {
          // Back before they could stop: they must be braking at least at the configured rate.
          const double braking_s = std::max(0.0, ms_between(t0, first->when) - o_.stop_bound.count()) / 1000.0;
          const double v_max = std::max(0.0, std::fabs(at_fault->v) - decel_v_ * braking_s) + 0.02;
          const double w_max = std::max(0.0, std::fabs(at_fault->omega) - decel_w_ * braking_s) + 0.05;
          char buf[200];
          std::snprintf(buf, sizeof buf, "; back after %.0f ms, drives still braking: v %.2f->%.2f m/s, w %.2f->%.2f rad/s",
                        ms_between(t0, first->when), std::fabs(at_fault->v), std::fabs(first->v), std::fabs(at_fault->omega),
                        std::fabs(first->omega));
          row.note += buf;
          if (std::fabs(first->v) > v_max || std::fabs(first->omega) > w_max) {
            ok = false;
            row.note += " (slower than the configured deceleration)";
          }
        }
      }
    } else {
      row.v_at_fault = v0;
      row.omega_at_fault = w0;
      if (at_fault->zero()) {
        row.note += "; robot at rest at the fault: braking not exercised";
        if (truth) ok = false;  // the stack drives: a drive row must be measured while moving
      }
      // First sample from which every sample up to `end` is zero.
      std::optional<Clock::time_point> zero_from;
      size_t zero_index = 0, last_index = 0;
      std::optional<size_t> first_rest;  // the first sample at rest (before any motion again)
      const BusObserver::VelocitySample* last = nullptr;
      for (size_t i = 0; i < odo.size(); ++i) {
        const auto& m = odo[i];
        if (m.when < t0 || m.when > end) continue;
        last = &m;
        last_index = i;
        if (m.zero() && !first_rest) first_rest = i;
        if (!m.zero()) zero_from.reset();
        else if (!zero_from) {
          zero_from = m.when;
          zero_index = i;
        }
      }
      // At rest and then driven again while the process is down or hung: a stale command got
      // through (e.g. from a hung commander let run again to stop).
      if (first_rest && (!zero_from || zero_index > *first_rest) && !at_fault->zero()) {
        double v_peak = 0;
        Clock::time_point when{};
        for (size_t i = *first_rest; i < odo.size() && odo[i].when <= end; ++i)
          if (std::fabs(odo[i].v) >= v_peak) {
            v_peak = std::fabs(odo[i].v);
            when = odo[i].when;
          }
        char buf[160];
        std::snprintf(buf, sizeof buf, "; at rest after %.0f ms, then moved again (%.3f m/s at %.0f ms)",
                      ms_between(t0, odo[*first_rest].when), v_peak, ms_between(t0, when));
        row.note += buf;
        ok = false;
      }
      // Back before it had to stop (collision avoidance back before the lld gave up its
      // trajectory): nothing to brake for.
      const bool back_in_time = ms_between(t0, end) <= stop_bound;
      if (back_in_time) row.note += "; back before it had to stop";
      if (truth && last && !at_fault->zero() && !back_in_time) {
        // Braking began: the start of the fall that ends at rest (or at the window's end).
        // From rest, or from the last sample; a robot that no longer translates but still
        // steers a little has ended its braking where translation stopped.
        // Translating at the fault: the fall of v, which ended where the robot stopped translating
        // (a controlled stop may still steer a little); turning in place: the fall of omega.
        const bool rotation = v0 < 0.05;
        size_t k = first_rest ? *first_rest : last_index;
        while (!rotation && k > 0 && odo[k - 1].when >= t0 && std::fabs(odo[k].v) < 1e-3 &&
               std::fabs(odo[k - 1].v) < 1e-3)
          --k;
        const auto onset = brake_onset(odo, k, t0 - std::chrono::seconds(2), rotation);
        if (onset) {
          row.brake_start_ms = std::max(0.0, ms_between(t0, *onset));
          double v_peak = v0, w_peak = w0;
          for (const auto& m : odo)
            if (m.when >= t0 && m.when <= *onset) {
              v_peak = std::max(v_peak, std::fabs(m.v));
              w_peak = std::max(w_peak, std::fabs(m.omega));
            }
          brake_ms = 1000.0 * std::max(v_peak / stop_decel_v(), w_peak / stop_decel_w()) + kBrakeSlackMs;
          if (*onset < t0) row.note += "; already slowing at the fault";
          if (*row.brake_start_ms > stop_bound) {
            ok = false;
            row.note += "; braking began later than " + std::to_string(static_cast<int>(stop_bound)) + " ms";
            // Had it begun braking earlier and then been driven again? (Named: the cause differs.)
            double v_min = std::fabs(at_fault->v);
            std::optional<Clock::time_point> fell;
            for (const auto& m : odo) {
              if (m.when < t0 || m.when > *onset) continue;
              const double v = std::fabs(m.v);
              if (!fell && v < std::fabs(at_fault->v) - 0.02) fell = m.when;
              if (fell && v > v_min + 0.02) {
                char buf[160];
                std::snprintf(buf, sizeof buf, " (it had begun braking at %.0f ms, then was driven again: %.2f -> %.2f m/s at %.0f ms)",
                              ms_between(t0, *fell), v_min, v, ms_between(t0, m.when));
                row.note += buf;
                break;
              }
              v_min = std::min(v_min, v);
            }
          }
        } else {
          ok = false;
          row.note += "; no braking seen";
        }
      }
      // Speeding up again after the stop bound (a resumed commander sending stale commands):
      // named, as it is what delays the stop.
      {
        double v_at_bound = -1, v_max_after = 0;
        for (const auto& m : odo) {
          if (m.when < t0 + std::chrono::milliseconds(static_cast<int64_t>(stop_bound)) || m.when > end) continue;
          if (v_at_bound < 0) v_at_bound = std::fabs(m.v);
          v_max_after = std::max(v_max_after, std::fabs(m.v));
        }
        if (v_at_bound >= 0 && v_max_after > v_at_bound + 0.02) {
          char buf[120];
          std::snprintf(buf, sizeof buf, "; sped up again after %.0f ms: %.2f -> %.2f m/s", stop_bound, v_at_bound, v_max_after);
          row.note += buf;
        }
      }
      row.drive_bound_ms = stop_bound + brake_ms;
      if (zero_from) {
        row.drive_zero_ms = ms_between(t0, *zero_from);
        if (*row.drive_zero_ms > *row.drive_bound_ms) {
          ok = false;
          row.note += "; measured velocity at zero later than " + std::to_string(static_cast<int>(*row.drive_bound_ms)) + " ms";
        }
      } else if (back_in_time) {
        // Reported, not bounded.
      } else if (last && ms_between(t0, end) < *row.drive_bound_ms) {
        // Back before the robot could have stopped: it must have been braking at least at the
        // chain's slowest stop deceleration once the bound for the stop had passed.
        const double braking_s = std::max(0.0, ms_between(t0, last->when) - stop_bound) / 1000.0;
        const double v_max = std::max(0.0, v0 - stop_decel_v() * braking_s) + 0.02;
        const double w_max = std::max(0.0, w0 - stop_decel_w() * braking_s) + 0.05;
        char buf[200];
        std::snprintf(buf, sizeof buf, "; back after %.0f ms, before it could stop: braked v %.2f->%.2f m/s, w %.2f->%.2f rad/s",
                      ms_between(t0, end), v0, std::fabs(last->v), w0, std::fabs(last->omega));
        row.note += buf;
        if (std::fabs(last->v) > v_max || std::fabs(last->omega) > w_max) {
          ok = false;
          row.note += " (slower than the configured deceleration)";
        }
      } else {
        ok = false;
        row.note += "; measured velocity not at zero before the process was back";
      }
    }
    // A stopped base driver acts on nothing: its drives stop on their own watchdog, so the
    // hold's timing (it follows detection) is reported, not bounded.
    const double cmd_bound = stop_bound + (nonzero_after > 0 ? brake_ms : 0.0);
    if (cmd_zero && !consumer && *row.cmd_zero_ms > cmd_bound) {
      ok = false;
      row.note += "; BASE_CMD at zero later than " + std::to_string(static_cast<int>(cmd_bound)) + " ms";
    }
    if (consumer && truth)
      row.robot_stopped_ms = row.drive_zero_ms;  // the hold follows detection: reported above, not the stop
    else if (row.cmd_zero_ms || row.drive_zero_ms)
      row.robot_stopped_ms = std::max(row.cmd_zero_ms.value_or(0.0), row.drive_zero_ms.value_or(0.0));
    drive_ok_ = ok;
  }

  struct VelocitySampleRef
  {
    const BusObserver::VelocitySample* sample = nullptr;
    size_t index = 0;
  };
  static VelocitySampleRef last_nonzero(const std::vector<BusObserver::VelocitySample>& v, Clock::time_point from, Clock::time_point to)
  {
    VelocitySampleRef r;
    for (size_t i = 0; i < v.size(); ++i)
      if (v[i].when >= from && v[i].when <= to && !v[i].zero() && !v[i].from_supervisor) r = {&v[i], i};
    return r;
  }

  int old_pid_for(const std::string& name) const
  {
    const auto s = obs_->status(name);
    return s ? s->pid : 0;
  }

  size_t log_size() const
  {
    std::ifstream in(o_.log_file, std::ios::ate | std::ios::binary);
    return in ? static_cast<size_t>(in.tellg()) : 0;
  }

  // What a restarted stateful process reports it reloaded, from the supervisor's log (the
  // children write to it) after `offset`: the scan mapper's "resuming from persisted state
  // ... (N scans", rg_kernel's "resumed from ...: N inputs replayed"; a fresh start is 0.
  std::optional<int64_t> reloaded(size_t offset, const std::string& process) const
  {
    std::ifstream in(o_.log_file, std::ios::binary);
    if (!in) return std::nullopt;
    in.seekg(static_cast<std::streamoff>(offset));
    static const std::regex mapper(R"(resuming from persisted state .* \((\d+) scans)");
    static const std::regex kernel(R"(resumed from .*: (\d+) inputs replayed)");
    const bool is_mapper = process == mapper_proc_;
    const std::string tag = "[" + process + "]";
    std::string line;
    std::optional<int64_t> n;
    std::smatch m;
    while (std::getline(in, line)) {
      if (line.find(tag) == std::string::npos) continue;
      if (std::regex_search(line, m, is_mapper ? mapper : kernel)) n = std::stoll(m[1]);
      else if (line.find(is_mapper ? "starting a new map" : "starting a fresh map") != std::string::npos) n = 0;
    }
    return n;
  }

  // State after a restart equals state before: for the RG map keeper, its first RG_MAP from
  // the new instance against its last one before the fault; for the scan mapper, the scans in
  // its reloaded checkpoint against the scans it had published.
  // rg_kernel: its journal replays at least every input the old instance had acknowledged
  // (heartbeat messages_in), and the map it restores is at least the last one it published
  // before the fault (version; same version = same regions and gateways). The scan mapper:
  // its checkpoint holds every scan it had published. `in_before`: the old instance's
  // accepted inputs at its last heartbeat before the fault.
  void check_restart_state(const std::string& name, Clock::time_point t0, Clock::time_point t_new, size_t log_offset,
                           int64_t in_before, FaultRow& row)
  {
    if (name == rg_map_proc_) {
      std::optional<int64_t> n;
      obs_->wait_until([&] { return (n = reloaded(log_offset, name)).has_value(); }, std::chrono::seconds(5));
      const int64_t expected = rg_base_ + in_before;
      if (!n) {
        row.state_lost = true;
        row.note += "; the restarted rg_kernel did not report its journal";
        return;
      }
      row.state_lost = *n < expected;
      row.note += "; journal replayed " + std::to_string(*n) + " inputs, >= " + std::to_string(expected) + " acknowledged";
      rg_base_ = *n;
      const BusObserver::MapSample* before = nullptr;
      for (const auto& m : obs_->rg_maps())
        if (m.when < t0) before = &m;
      if (!before) {
        row.note += "; no RG_MAP before the fault";
        return;
      }
      const auto b = *before;
      // The restored map: what the new instance publishes before its live input begins (its
      // heartbeats count accepted inputs); the newest of those, since replay goes forward.
      const auto s_new = obs_->status(name);
      const int new_pid = s_new ? s_new->pid : 0;
      std::optional<Clock::time_point> live;
      obs_->wait_until([&] { return (live = obs_->first_heartbeat_with_input(name, new_pid, t_new)).has_value(); },
                       std::chrono::seconds(15));
      const BusObserver::MapSample* restored = nullptr;
      int stale = 0;
      for (const auto& m : obs_->rg_maps()) {
        if (m.when < t_new || (live && m.when > *live)) continue;
        if (m.version < b.version) ++stale;
        if (!restored || m.version >= restored->version) restored = &m;
      }
      if (restored && restored->version < b.version) --stale;  // the restored one is counted on its own
      if (!restored) {
        row.state_lost = true;
        row.note += "; no RG_MAP within 5 s of the restart";
        return;
      }
      const bool older = restored->version < b.version;
      const bool differs = restored->version == b.version && (restored->region_ids != b.region_ids || restored->gateway_ids != b.gateway_ids);
      row.state_lost = *row.state_lost || older || differs;
      row.note += "; RG_MAP v" + std::to_string(b.version) + " (" + std::to_string(b.region_ids.size()) + " regions) before, restored v" +
                  std::to_string(restored->version) + " (" + std::to_string(restored->region_ids.size()) + " regions)";
      if (differs) row.note += " with other regions/gateways";
      if (stale > 0) row.note += "; " + std::to_string(stale) + " older RG_MAP versions republished during the journal replay";
    } else if (name == planner_proc_) {
      // The goal it pursued before the fault (OK or waiting for a path) is pursued after it: the
      // new instance's first GLOBAL_PATH names the same goal, neither cancelled nor forgotten.
      const BusObserver::PathSample* before = nullptr;
      for (const auto& p : obs_->paths())
        if (p.when < t0) before = &p;
      if (!before || (before->status != global_path_t::STATUS_OK && before->status != global_path_t::STATUS_NO_PATH)) {
        row.note += "; no goal pursued before the fault";
        return;
      }
      const int64_t goal = before->goal_id;
      std::optional<BusObserver::PathSample> after;
      obs_->wait_until([&] {
        for (const auto& p : obs_->paths())
          if (p.when >= t_new) return (after = p).has_value();
        return false;
      }, std::chrono::seconds(5));
      const bool kept = after && after->goal_id == goal &&
                        (after->status == global_path_t::STATUS_OK || after->status == global_path_t::STATUS_NO_PATH);
      row.state_lost = !kept;
      row.note += "; goal " + std::to_string(goal) + " before, " +
                  (after ? "goal " + std::to_string(after->goal_id) + " status " + std::to_string(after->status) + " after"
                         : std::string("no GLOBAL_PATH within 5 s of the restart"));
    } else if (name == explorer_proc_) {
      // What it had explored before the fault it still has after it: the new instance's first
      // EXPLORER_STATUS holds at least the stacked gateways and goals sent, and is not back to
      // exploring once it was done.
      const BusObserver::ExplorerSample* before = nullptr;
      for (const auto& e : obs_->explorer_states())
        if (e.when < t0) before = &e;
      if (!before) {
        row.note += "; no EXPLORER_STATUS before the fault";
        return;
      }
      const BusObserver::ExplorerSample b = *before;
      std::optional<BusObserver::ExplorerSample> after;
      obs_->wait_until([&] {
        for (const auto& e : obs_->explorer_states())
          if (e.when >= t_new) return (after = e).has_value();
        return false;
      }, std::chrono::seconds(5));
      const bool kept = after && after->stack >= b.stack && after->goals_sent >= b.goals_sent &&
                        (b.phase != explorer_status_t::PHASE_DONE || after->phase == explorer_status_t::PHASE_DONE);
      row.state_lost = !kept;
      const auto text = [](const BusObserver::ExplorerSample& e) {
        return "phase " + std::to_string(e.phase) + ", " + std::to_string(e.stack) + " stacked, " +
               std::to_string(e.goals_sent) + " goals";
      };
      row.note += "; " + text(b) + " before, " +
                  (after ? text(*after) + " after" : std::string("no EXPLORER_STATUS within 5 s of the restart"));
    } else if (name == mapper_proc_) {
      std::set<int64_t> published;
      for (const auto& a : obs_->aligned_scans())
        if (a.revision == 0 && a.when > mapper_instance_start_ && a.when < t_new) published.insert(a.scan_id);
      const int64_t expected = mapper_base_ + static_cast<int64_t>(published.size());
      std::optional<int64_t> n;
      obs_->wait_until([&] { return (n = reloaded(log_offset, name)).has_value(); }, std::chrono::seconds(5));
      if (!n) {
        row.state_lost = true;
        row.note += "; the restarted scan mapper did not report its checkpoint";
        return;
      }
      row.state_lost = *n < expected;
      row.note += "; checkpoint reloaded " + std::to_string(*n) + " scans, " + std::to_string(expected) + " published before";
      mapper_base_ = *n;
      mapper_instance_start_ = t_new;
    }
  }

  // Signed like rgnav_ctl's (the supervisor refuses anything else), each copy with a nonce of its own.
  void send_order(int8_t order, const std::string& target)
  {
    if (!order_key_) order_key_ = sup::load_order_key(o_.order_key_file);
    sup::OrderFields o;
    o.utime = time::wall_utime();
    o.order_id = ++order_id_;
    o.host = o_.host;
    o.order = order;
    o.target = target;
    o.source = sup::order_source("fault_harness");
    for (int i = 0; i < 3; ++i) {
      sup::sign_order(o, *order_key_);
      bus::publish(obs_->bus(), "SUPERVISOR_ORDERS", sup::to_order_msg(o));
    }
  }

  void run_fault(const sup::PlannedCommand& c, const std::string& fault, FaultRow& row)
  {
    const std::string& name = c.spec.name;
    if (done(name)) {
      row.status = "n/a";
      row.note = "a oneshot job that had finished before this fault";
      return;
    }
    if ((fault == "sigstop" || fault == "busy_loop") && !c.spec.heartbeat) {
      row.status = "n/a";
      row.note = "no heartbeat: a stopped process is invisible to the supervisor (its dependents notice)";
      return;
    }
    const auto log_offset = log_size();
    const int64_t in_before = obs_->heartbeat(name) ? obs_->heartbeat(name)->messages_in : 0;
    // What the current instance started from (it may have been restarted by an earlier fault).
    if (name == mapper_proc_ || name == rg_map_proc_) {
      const auto base = reloaded(0, name);
      (name == mapper_proc_ ? mapper_base_ : rg_base_) = base.value_or(0);
      if (name == mapper_proc_ && old_pid_for(name) != 0) {
        const int pid = old_pid_for(name);
        if (const auto t = obs_->first_status(name, Clock::time_point{}, [pid](const process_status_t& p) { return p.pid == pid; }))
          mapper_instance_start_ = *t;
      }
    }
    obs_->spin(std::chrono::milliseconds(200));
    const bool hang = fault == "sigkill" || fault == "sigstop" || fault == "busy_loop";
    // A drive-chain fault is measured while the robot moves: braking must be exercised.
    if (hang && obs_->has_truth() && is_drive_row(c) && !wait_moving(o_.moving_wait))
      row.note += "; robot not moving within " + std::to_string(o_.moving_wait.count() / 1000) + " s";
    const auto before = snapshot();
    const int old_pid = before.count(name) ? before.at(name).first : 0;
    const auto state_before = obs_->state(name);
    obs_->reset_gaps();
    // A busy loop keeps the heartbeat going: the supervisor sees its progress stand still for the
    // work timeout, counted from the first heartbeat after the loop stopped (up to a period later:
    // it still shows the turns made since the one before); then the stop grace. Both from the
    // process's last progress (below), which may come after the fault was sent.
    const auto work_timeout = c.spec.work_timeout_ms > 0 ? std::chrono::milliseconds(c.spec.work_timeout_ms) : o_.work_timeout;
    double detect_bound = static_cast<double>(
        ((fault == "busy_loop" ? work_timeout : o_.heartbeat_timeout) + o_.heartbeat_period).count()) + 100.0;
    const auto restart_bound = fault == "busy_loop" ? o_.restart_bound + work_timeout - o_.heartbeat_timeout : o_.restart_bound;
    // The supervisor moves its deadlines on by every stall of the whole host it measures: those
    // are added to the detection bound (reported in the note).
    const int64_t host_stall_before = obs_->last_status() ? obs_->last_status()->host_stall_total_ms : 0;
    bool ok = true;
    gaps_ok_ = true;
    drive_ok_ = true;
    auto t0 = Clock::now();

    if (hang) {
      if (fault == "busy_loop") {
        // The process's event loop spins (runtime/fault_injection.h) past the supervisor's
        // bound and its grace, so only the supervisor ends it.
        if (o_.busy_loop_mid_work) {
          const bool mid_work = obs_->wait_until([&] {
            const auto* hb = obs_->heartbeat(name);
            return hb && hb->pid == old_pid && hb->busy_ms >= 100 && hb->busy_ms < 300 &&
                   Clock::now() - hb->last < std::chrono::milliseconds(50);
          }, std::chrono::seconds(5));
          if (!mid_work) row.note += "; its loop not seen in a step of work: sent anyway";
          t0 = Clock::now();
        }
        fault_inject_t f;
        f.utime = time::wall_utime();
        f.target = name;
        f.pid = old_pid;
        f.fault = fault_inject_t::FAULT_BUSY_LOOP;
        f.duration_ms = static_cast<int32_t>((work_timeout + o_.hung_grace + std::chrono::seconds(5)).count());
        bus::publish(obs_->bus(), runtime::kFaultInjectChannel, f);
      } else {
        kill(old_pid, fault == "sigkill" ? SIGKILL : SIGSTOP);
      }
      const bool back = obs_->wait_until([&] { return obs_->first_heartbeat_new_pid(name, old_pid, t0).has_value() ||
                                                      (!c.spec.heartbeat && obs_->status(name) && obs_->status(name)->pid != old_pid &&
                                                       obs_->status(name)->state == process_status_t::STATE_RUNNING); },
                                         restart_bound + std::chrono::milliseconds(3000));
      if (fault == "sigstop") kill(old_pid, SIGCONT);  // in case the supervisor did not act
      const auto det = obs_->first_status(name, t0, [&](const process_status_t& p) {
        return p.pid != old_pid || p.state != process_status_t::STATE_RUNNING;
      });
      if (det) row.detect_ms = ms_between(t0, *det);
      // A busy loop begins when the process's loop takes the fault in, after the work under way
      // when it arrived (a scan being matched, a record written): until then the process
      // progressed, and the supervisor's bound on work without progress runs from its last
      // progress. Its heartbeats show when that was (their progress counter).
      double hang_from_ms = 0.0;
      if (fault == "busy_loop" && det) {
        if (const auto progressing = obs_->last_seen_progressing(name, old_pid, t0, *det)) {
          hang_from_ms = ms_between(t0, *progressing);
          row.hang_start_ms = hang_from_ms;
          if (hang_from_ms >= 50.0)
            row.note += "; still progressing " + std::to_string(static_cast<int>(hang_from_ms)) +
                        " ms after the fault was sent (work under way)";
        }
      }
      const int64_t host_stalled = (obs_->last_status() ? obs_->last_status()->host_stall_total_ms : 0) - host_stall_before;
      if (host_stalled > 0 && fault != "sigkill") {
        detect_bound += static_cast<double>(host_stalled);
        row.note += "; host stalled " + std::to_string(host_stalled) + " ms meanwhile (the supervisor's deadlines moved on)";
      }
      if (back) {
        auto t = obs_->first_heartbeat_new_pid(name, old_pid, t0);
        if (!t) t = obs_->first_status(name, t0, [&](const process_status_t& p) { return p.pid != old_pid && p.state == process_status_t::STATE_RUNNING; });
        if (t) row.restart_ms = ms_between(t0, *t);
      }
      const bool in_time = det && *row.detect_ms - hang_from_ms <= detect_bound;
      ok = in_time && back && row.restart_ms && *row.restart_ms - hang_from_ms <= restart_bound.count();
      if (!det) row.note += "; not detected";
      else if (!in_time)
        row.note += "; detected later than " + std::to_string(static_cast<int>(detect_bound)) + " ms" +
                    (hang_from_ms > 0.0 ? " after it was last seen progressing" : "") + " (its heartbeats, ms from the fault:+progress: " +
                    obs_->heartbeat_trace(name, old_pid, t0 - std::chrono::seconds(1), *det, t0) + ")";
      if (!back) row.note += "; not restarted";
      else if (!row.restart_ms || *row.restart_ms - hang_from_ms > restart_bound.count())
        row.note += "; running again later than the " + std::to_string(restart_bound.count()) + " ms bound";
      const auto t_new = obs_->first_status(name, t0, [&](const process_status_t& p) { return p.pid != 0 && p.pid != old_pid; });
      measure_drive(c, t0, back ? std::optional<Clock::time_point>(t0 + std::chrono::microseconds(static_cast<int64_t>(*row.restart_ms * 1000))) : std::nullopt, row);
      if (t_new) check_restart_state(name, t0, *t_new, log_offset, in_before, row);
    } else if (fault == "crash_loop") {
      // Kill every new instance at once until the supervisor gives up on it.
      int killed_pid = old_pid;
      kill(old_pid, SIGKILL);
      int kills = 1;
      const bool failed = obs_->wait_until(
          [&] {
            const auto s = obs_->status(name);
            if (!s) return false;
            if (s->state == process_status_t::STATE_FAILED) return true;
            if (s->pid != 0 && s->pid != killed_pid) {
              killed_pid = s->pid;
              kill(killed_pid, SIGKILL);
              ++kills;
            }
            return false;
          },
          std::chrono::seconds(60));
      if (failed) {
        row.detect_ms = ms_between(t0, *obs_->first_status(name, t0, [](const process_status_t& p) {
          return p.state == process_status_t::STATE_FAILED;
        }));
        const auto* st = obs_->last_status();
        row.note += "; FAILED after " + std::to_string(kills) + " kills, alert: \"" + (st ? st->alert : "") + "\"";
        if (!st || st->alert.empty()) ok = false;
        obs_->spin(std::chrono::milliseconds(300));
        check_others(name, before, row);  // the others kept running while it was failing
        const auto t1 = Clock::now();
        send_order(supervisor_order_t::ORDER_START, name);
        const bool back = obs_->wait_until([&] {
          const auto s = obs_->status(name);
          return s && s->state == process_status_t::STATE_RUNNING && s->pid != killed_pid;
        }, o_.restart_bound + std::chrono::milliseconds(3000));
        if (back) row.restart_ms = ms_between(t1, Clock::now());
        else row.note += "; not restarted by a start order";
        ok = ok && back;
        if (back) check_restart_state(name, t0, t1, log_offset, in_before, row);
      } else {
        ok = false;
        row.note += "; never marked FAILED after " + std::to_string(kills) + " kills";
      }
    } else if (fault == "flood" || fault == "malformed" || fault == "loss_dup_delay") {
      if (c.spec.inputs.empty()) {
        row.status = "n/a";
        row.note = "no inputs declared";
        return;
      }
      const int64_t dropped_before = obs_->heartbeat(name) ? obs_->heartbeat(name)->dropped : 0;
      // A drive-chain process that drove before bad input must drive again after it: input it
      // dropped or survived must not leave the robot stopped for good.
      const bool drove_before = obs_->has_truth() && is_drive_row(c) && wait_moving(std::chrono::seconds(5));
      if (obs_->has_truth() && is_drive_row(c) && !drove_before)
        row.note += "; robot not driving before the fault (an earlier one may have left it stopped)";
      if (fault == "loss_dup_delay") {
        // A relay of this stack in front of one of its inputs is switched to impair for 2 s.
        const sup::PlannedCommand* relay = nullptr;
        for (const auto* r : local_)
          for (const auto& in : c.spec.inputs)
            if (arg_after(r->argv, "--to") == in && !r->executable.empty()) relay = r;
        if (!relay) {
          row.status = "pending";
          row.note = "no lcm_relay in front of its inputs in this launch config";
          return;
        }
        const auto rs = obs_->status(relay->spec.name);
        if (!rs || rs->pid == 0) {
          row.status = "fail";
          row.note = "relay " + relay->spec.name + " not running";
          return;
        }
        kill(rs->pid, SIGUSR1);
        obs_->spin(std::chrono::milliseconds(2000));
        kill(rs->pid, SIGUSR2);
        row.note += "; impaired by " + relay->spec.name;
      } else {
        std::mt19937 rng(42);
        const int n = fault == "flood" ? o_.flood_messages : 1000;
        // The material: what each input carried before. The harness hears its own injections, so
        // captures stop meanwhile (a truncated copy must not become the next "valid" one).
        std::map<std::string, std::vector<uint8_t>> material;
        for (const auto& in : c.spec.inputs)
          if (const auto* v = obs_->captured_input(in)) material[in] = *v;
        obs_->capture_inputs(false);
        for (int i = 0; i < n; ++i) {
          for (const auto& in : c.spec.inputs) {
            const auto it = material.find(in);
            const auto* valid = it == material.end() || it->second.size() <= 8 ? nullptr : &it->second;
            std::vector<uint8_t> msg;
            if (fault == "flood" && valid) {
              msg = *valid;
            } else if (valid && i % 3 == 0) {
              msg.assign(valid->begin(), valid->begin() + static_cast<long>(rng() % valid->size()));  // truncated
            } else if (valid && i % 3 == 1) {
              msg = *valid;
              msg[8 + rng() % (msg.size() - 8)] ^= static_cast<uint8_t>(1 + rng() % 255);  // corrupted after the fingerprint
            } else {
              msg.resize(1 + rng() % 512);
              for (auto& b : msg) b = static_cast<uint8_t>(rng());
            }
            obs_->bus().publish(in, msg.data(), msg.size());
          }
          // Paced (a runaway publisher, not a denial of service): LCM's udpm delivers every
          // datagram to every process on the host, which filters channels in user space, so an
          // unpaced flood on any channel loads them all.
          if (i % 20 == 19) {
            // What waits in this observer's queue is read between batches even when the flood is
            // behind its pace: a queue left to fill dropped heartbeats sent on time.
            obs_->bus().handle(std::chrono::milliseconds(0));
            const auto due = t0 + std::chrono::microseconds(static_cast<int64_t>(1e6 * (i + 1) / o_.flood_rate_hz));
            while (Clock::now() < due) obs_->bus().handle(std::chrono::duration_cast<std::chrono::milliseconds>(due - Clock::now()) + std::chrono::milliseconds(1));
          }
        }
        if (fault == "flood" && !material.count(c.spec.inputs[0])) row.note += "; no valid input captured: flooded with random bytes";
        obs_->spin(std::chrono::milliseconds(1000));
        obs_->capture_inputs(true);
      }
      const auto s = obs_->status(name);
      const bool same = s && s->pid == old_pid && before.count(name) && s->restarts == before.at(name).second;
      const double own_gap = static_cast<double>(obs_->gap_now(name).count());
      if (!same) row.note += "; the process itself was restarted";
      if (own_gap > o_.heartbeat_timeout.count())
        row.note += "; its own heartbeat stopped for " + std::to_string(static_cast<int>(own_gap)) + " ms" + lost_on_the_way(name);
      // Gaps are judged by when heartbeats were sent; how late this observer read them says how
      // much of the flood its own receive queue held.
      if (obs_->max_late() > o_.heartbeat_timeout)
        row.note += "; heartbeats read here up to " + std::to_string(obs_->max_late().count()) + " ms after they were sent";
      if (fault == "malformed") {
        const int64_t dropped = obs_->heartbeat(name) ? obs_->heartbeat(name)->dropped - dropped_before : 0;
        row.note += (row.note.empty() ? "" : "; ") + std::to_string(dropped) + " inputs dropped as invalid";
      }
      ok = same && own_gap <= o_.heartbeat_timeout.count();
      if (drove_before && !wait_moving(o_.moving_wait)) {
        ok = false;
        row.note += "; the robot did not drive again within " + std::to_string(o_.moving_wait.count() / 1000) + " s";
      }
    }

    if (fault != "crash_loop") {
      obs_->spin(std::chrono::milliseconds(200));
      check_others(name, before, row);
    }
    if (state_before) {
      obs_->wait_until([&] { return obs_->first_state_since(name, t0 + std::chrono::milliseconds(1)).has_value(); },
                       std::chrono::milliseconds(3000));
      const auto after = obs_->first_state_since(name, Clock::now() - std::chrono::milliseconds(500));
      const auto first_after = obs_->first_state_since(name, t0);
      row.state_lost = !first_after || *first_after < *state_before;
      if (*row.state_lost) row.note += "; state " + std::to_string(*state_before) + " before, " + (first_after ? std::to_string(*first_after) : "none") + " after";
      (void)after;
    }
    if (!drive_ok_) ok = false;
    ok = ok && !row.others_restarted && gaps_ok_ && !(row.state_lost && *row.state_lost);
    if (row.status.empty()) row.status = ok ? "pass" : "fail";
    if (!row.note.empty() && row.note.rfind("; ", 0) == 0) row.note = row.note.substr(2);
  }

  // The whole host stalls for `stall` while the robot drives: every process of the stack and
  // the supervisor stopped together, then continued together (the scheduler picks the order,
  // real-time threads first, as after a VM's pause). Nobody is hung, so nothing may be restarted,
  // and the drive chain must not stop the robot: no drive fault reported (a heartbeat or TPDO
  // consumer that timed out), and the robot not at rest within the 2 s after.
  FaultRow host_stall(std::chrono::milliseconds stall)
  {
    FaultRow row;
    row.process = "host";
    row.fault = "stall_" + std::to_string(stall.count()) + "ms";
    if (!wait_all_running(std::chrono::seconds(15))) row.note += "; stack not running before the stall";
    if (obs_->has_truth() && !wait_moving(o_.moving_wait))
      row.note += "; robot not moving within " + std::to_string(o_.moving_wait.count() / 1000) + " s";
    obs_->spin(std::chrono::milliseconds(200));
    const auto before = snapshot();
    std::vector<pid_t> pids;
    for (const auto& [name, pr] : before)
      if (pr.first > 0) pids.push_back(pr.first);
    pids.push_back(sup_pid_);
    const auto& moved = obs_->has_truth() ? obs_->truth() : obs_->drive_odometry();
    const BusObserver::VelocitySample at = moved.empty() ? BusObserver::VelocitySample{} : moved.back();
    row.v_at_fault = std::fabs(at.v);
    row.omega_at_fault = std::fabs(at.omega);
    obs_->reset_gaps();
    const auto t0 = Clock::now();
    for (const pid_t p : pids) kill(p, SIGSTOP);
    std::this_thread::sleep_for(stall);
    for (const pid_t p : pids) kill(p, SIGCONT);
    obs_->spin(std::chrono::milliseconds(2000) + stall);
    bool fault = false, rest = false;
    double v_min = std::fabs(at.v);
    for (const auto& m : obs_->drive_odometry())
      if (m.when >= t0 && m.fault) fault = true;
    for (const auto& m : moved) {
      if (m.when < t0) continue;
      v_min = std::min(v_min, std::fabs(m.v));
      if (m.zero()) rest = true;
    }
    row.v_min_after = v_min;
    row.stall_stop = fault || (rest && !at.zero());
    if (fault) row.note += "; the base driver reported a drive fault";
    if (rest && !at.zero()) row.note += "; the robot came to rest";
    if (at.zero()) row.note += "; robot at rest at the stall: not exercised";
    // Nobody was hung: nothing may have been restarted.
    for (const auto& [name, pr] : before) {
      const auto s = obs_->status(name);
      if (!s || s->pid != pr.first || s->restarts != pr.second) {
        row.others_restarted = true;
        row.note += "; " + name + " restarted";
      }
    }
    row.status = !*row.stall_stop && !row.others_restarted && !at.zero() ? "pass" : "fail";
    if (row.note.rfind("; ", 0) == 0) row.note = row.note.substr(2);
    return row;
  }

  FaultRow supervisor_fault()
  {
    FaultRow row;
    row.process = "supervisor";
    row.fault = "sigkill_adopt";
    const auto before = snapshot();
    kill(sup_pid_, SIGKILL);
    waitpid(sup_pid_, nullptr, 0);
    sup_pid_ = 0;
    const auto t0 = Clock::now();
    obs_->spin(std::chrono::milliseconds(300));
    start_supervisor();
    const bool up = wait_all_running(std::chrono::seconds(10));
    bool ok = up;
    if (up) row.restart_ms = ms_between(t0, Clock::now());
    else row.note += "; stack not running under the new supervisor";
    int dups = 0;
    for (const auto* c : running_commands()) {
      if (c->spec.oneshot && before.count(c->spec.name) == 0) continue;  // done before the kill
      const auto s = obs_->status(c->spec.name);
      if (!s || before.count(c->spec.name) == 0 || s->pid != before.at(c->spec.name).first) {
        row.others_restarted = true;
        row.note += "; " + c->spec.name + " not adopted";
      }
      const int n = count_instances(c->argv);
      if (n != 1) {
        ++dups;
        row.note += "; " + std::to_string(n) + " instances of " + c->spec.name;
      }
    }
    // An adopted child that dies is noticed through /proc and restarted.
    const auto cmds = running_commands();
    if (up && !cmds.empty()) {
      const auto& name = cmds.back()->spec.name;
      const int pid = obs_->status(name)->pid;
      const auto t1 = Clock::now();
      kill(pid, SIGKILL);
      const auto restarted = [&] { return obs_->first_heartbeat_new_pid(name, pid, t1).has_value(); };
      const auto detected = [&] {
        return obs_->first_status(name, t1, [&](const process_status_t& p) { return p.pid != pid; });
      };
      // Both: the new child's heartbeat can arrive before the supervisor's status that reports it
      // (seen once under a loaded ./rgnav test: detect "-" with the child back).
      obs_->wait_until([&] { return restarted() && detected().has_value(); },
                       o_.restart_bound + std::chrono::milliseconds(3000));
      const bool back = restarted();
      const auto det = detected();
      if (det) row.detect_ms = ms_between(t1, *det);
      row.note += "; killed adopted " + name + (back ? ", restarted" : ", NOT restarted");
      ok = ok && back && det;
    }
    ok = ok && !row.others_restarted && dups == 0;
    row.status = ok ? "pass" : "fail";
    if (row.note.rfind("; ", 0) == 0) row.note = row.note.substr(2);
    return row;
  }

  HarnessOptions o_;
  sup::LaunchPlan plan_;
  std::vector<const sup::PlannedCommand*> local_;
  std::unique_ptr<BusObserver> obs_;
  std::map<std::string, std::chrono::milliseconds> baseline_gap_;
  std::map<std::string, std::string> blocked_;  // process -> the unbuilt dependency
  pid_t sup_pid_ = 0;
  Clock::time_point sup_started_{};
  int64_t order_id_ = 1000;
  std::optional<sup::OrderKey> order_key_;
  bool gaps_ok_ = true;
  bool drive_ok_ = true;
  std::string rg_map_proc_, mapper_proc_, base_proc_, planner_proc_, explorer_proc_, lld_proc_, ca_proc_;
  double decel_v_ = 1.0, decel_w_ = 1.0;          // the base driver's ramps (its deadman stop)
  double sim_brake_decel_ = 0.0, sim_alpha_ = 0.0;  // the simulated body's braking limits (0: unknown)
  double lld_decel_v_ = 0.0, lld_decel_w_ = 0.0;  // the lld's controlled stop (0: no lld)
  double lld_trajectory_timeout_s_ = 0.0;
  int64_t mapper_base_ = 0;                  // scans the mapper's current instance resumed with
  int64_t rg_base_ = 0;                      // journal inputs rg_kernel's current instance replayed
  Clock::time_point mapper_instance_start_{};
};

}  // namespace

std::vector<FaultRow> run_harness(const HarnessOptions& options)
{
  Harness h(options);
  return h.run();
}

}  // namespace rgnav::fault
