#include "supervisor.h"

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <spdlog/spdlog.h>

#include "child_process.h"
#include "state_file.h"

namespace rgnav::supervisor {

const char* to_string(ProcState s)
{
  switch (s) {
    case ProcState::kStopped: return "stopped";
    case ProcState::kStarting: return "starting";
    case ProcState::kRunning: return "running";
    case ProcState::kHung: return "hung";
    case ProcState::kBackoff: return "backoff";
    case ProcState::kFailed: return "FAILED";
    case ProcState::kStopping: return "stopping";
  }
  return "?";
}

Supervisor::Supervisor(LaunchPlan plan, std::string host, SupervisorOptions options, std::string state_dir)
    : plan_(std::move(plan)), host_(std::move(host)), options_(std::move(options)), state_dir_(std::move(state_dir))
{
  make_dirs(state_dir_);
  for (const auto& c : plan_.commands) {
    if (!c.spec.host.empty() && c.spec.host != host_) continue;
    Entry e(options_.restart);
    e.cmd = &c;
    e.missing = c.executable.empty();
    if (e.missing) e.last_exit = "missing executable";
    e.safety_critical = c.spec.safety_critical ||
                        std::find(options_.safety_critical.begin(), options_.safety_critical.end(), c.spec.name) !=
                            options_.safety_critical.end();
    e.auto_respawn = c.spec.auto_respawn_set ? c.spec.auto_respawn : options_.default_auto_respawn;
    e.heartbeat_timeout = c.spec.heartbeat_timeout_ms > 0 ? std::chrono::milliseconds(c.spec.heartbeat_timeout_ms)
                                                         : options_.heartbeat_timeout;
    e.startup_timeout = c.spec.startup_timeout_ms > 0 ? std::chrono::milliseconds(c.spec.startup_timeout_ms)
                                                     : options_.startup_timeout;
    e.work_timeout = c.spec.work_timeout_ms > 0 ? std::chrono::milliseconds(c.spec.work_timeout_ms) : options_.work_timeout;
    entries_.push_back(std::move(e));
  }
}

Supervisor::Entry* Supervisor::find(const std::string& name)
{
  for (auto& e : entries_)
    if (e.cmd->spec.name == name) return &e;
  return nullptr;
}

Supervisor::Entry* Supervisor::find_pid(pid_t pid)
{
  if (pid <= 0) return nullptr;
  for (auto& e : entries_)
    if (e.pid == pid) return &e;
  return nullptr;
}

std::vector<Supervisor::Entry*> Supervisor::targets(const std::string& target)
{
  std::vector<Entry*> out;
  if (target.empty() || target == "everything") {
    for (auto& e : entries_) out.push_back(&e);
    return out;
  }
  if (Entry* e = find(target)) return {e};
  for (const CommandSpec* c : plan_.config.in_group(target))
    if (Entry* e = find(c->name)) out.push_back(e);
  return out;
}

void Supervisor::set_state(Entry& e, ProcState s)
{
  if (e.state == s) return;
  spdlog::debug("{}: {} -> {}", e.cmd->spec.name, to_string(e.state), to_string(s));
  e.state = s;
  changed_ = true;
}

void Supervisor::raise_alert(const std::string& text)
{
  spdlog::error("ALERT: {}", text);
  alert_ = text;
  new_alerts_.push_back(text);
  changed_ = true;
}

std::vector<std::string> Supervisor::take_alerts() { return std::exchange(new_alerts_, {}); }

bool Supervisor::take_changed() { return std::exchange(changed_, false); }

void Supervisor::save()
{
  SupervisorState s;
  s.host = host_;
  s.launch_config = plan_.config.file;
  for (const auto& e : entries_) {
    if (e.pid == 0) continue;
    s.children.push_back({e.cmd->spec.name, e.pid, e.start_ticks, e.cmd->argv, e.cmd->spec.stop_signal, e.restarts});
  }
  for (const auto& o : orphans_) s.children.push_back({o.name, o.pid, o.start_ticks, read_cmdline(o.pid), SIGTERM, 0});
  if (!shutting_down_)
    for (const auto& e : entries_)
      if (e.done) s.done.push_back(e.cmd->spec.name);
  try {
    save_state(state_path(), s);
  } catch (const std::exception& ex) {
    spdlog::error("{}", ex.what());
  }
}

void Supervisor::recover(Clock::time_point now)
{
  const SupervisorState old = load_state(state_path());
  for (const auto& name : old.done) {
    Entry* e = find(name);
    if (e && e->cmd->spec.oneshot && old.launch_config == plan_.config.file) {
      spdlog::info("{} finished under the previous supervisor: not run again", name);
      e->done = true;
      e->last_exit = "done (exit 0)";
    }
  }
  for (const auto& r : old.children) {
    if (!same_process_alive(r.pid, r.start_ticks)) continue;
    const auto cmdline = read_cmdline(r.pid);
    if (cmdline != r.argv) continue;  // the pid now belongs to someone else
    Entry* e = find(r.name);
    if (e && e->pid == 0 && e->cmd->argv == r.argv) {
      e->restarts = r.restarts;
      adopt(*e, r.pid, r.start_ticks, now);
    } else {
      spdlog::warn("stopping {} (pid {}) left by a previous supervisor: no longer in the launch config", r.name, r.pid);
      signal_child(r.pid, r.stop_signal);
      signal_child(r.pid, SIGCONT);
      orphans_.push_back({r.name, r.pid, r.start_ticks, now + options_.orphan_grace, false});
    }
  }
  // A lost state file: the lock files still name the live holders.
  for (auto& e : entries_) {
    if (e.pid != 0) continue;
    const auto holder = lock_holder(lock_path(e.cmd->spec.name));
    if (holder && same_process_alive(holder->first, holder->second) && read_cmdline(holder->first) == e.cmd->argv)
      adopt(e, holder->first, holder->second, now);
  }
  save();
}

void Supervisor::adopt(Entry& e, pid_t pid, uint64_t start_ticks, Clock::time_point now)
{
  spdlog::info("adopting {} (pid {}) started by a previous supervisor", e.cmd->spec.name, pid);
  e.pid = pid;
  e.start_ticks = start_ticks;
  e.adopted = true;
  e.want_running = true;
  e.started = now;
  e.last_heartbeat.reset();
  e.progress = -1;
  e.seq = -1;
  e.intent = StopIntent::kNone;
  set_state(e, e.cmd->spec.heartbeat ? ProcState::kStarting : ProcState::kRunning);
}

void Supervisor::start_all(Clock::time_point now)
{
  for (auto& e : entries_) {
    if (e.missing) {
      spdlog::warn("{}: not started, executable missing ({})", e.cmd->spec.name, e.cmd->argv[0]);
      continue;
    }
    if (e.done) continue;  // a oneshot finished before this supervisor took over
    e.want_running = true;
  }
  tick(now);
}

bool Supervisor::order(Order order, const std::string& target, Clock::time_point now, std::string* why)
{
  if (order == Order::kShutdown) {
    shutdown(now);
    return true;
  }
  auto list = targets(target);
  if (list.empty()) {
    if (why) *why = "no process or group \"" + target + "\" on host " + host_;
    return false;
  }
  for (Entry* e : list) {
    switch (order) {
      case Order::kStart:
        if (e->missing) break;
        e->policy.reset();
        e->done = false;
        e->want_running = true;
        if (e->state == ProcState::kFailed || e->state == ProcState::kBackoff) set_state(*e, ProcState::kStopped);
        break;
      case Order::kStop:
        e->want_running = false;
        e->down_unplanned = false;  // the operator's decision: nothing to hold for
        if (e->pid != 0) {
          begin_stop(*e, StopIntent::kOperator, now);
        } else {
          set_state(*e, ProcState::kStopped);
        }
        break;
      case Order::kRestart:
        if (e->missing) break;
        e->policy.reset();
        e->done = false;
        e->want_running = true;
        if (e->pid != 0) {
          begin_stop(*e, StopIntent::kRestart, now);
        } else {
          set_state(*e, ProcState::kStopped);
        }
        break;
      case Order::kShutdown: break;
    }
  }
  tick(now);
  return true;
}

void Supervisor::shutdown(Clock::time_point now)
{
  if (!shutting_down_) spdlog::info("shutting down: stopping {} processes", entries_.size());
  shutting_down_ = true;
  for (auto& e : entries_) e.want_running = false;
  tick(now);
}

bool Supervisor::finished() const
{
  if (!shutting_down_ || !orphans_.empty()) return false;
  return std::all_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.pid == 0; });
}

bool Supervisor::dependencies_up(const Entry& e, Clock::time_point now) const
{
  for (const auto& d : e.cmd->spec.depends) {
    const Entry* local = nullptr;
    for (const auto& x : entries_)
      if (x.cmd->spec.name == d) local = &x;
    if (local) {
      // A job is a dependency once it has done its work (its output exists), a service while it
      // runs. A service the operator stopped holds nothing back: it is not coming back, and a
      // dependent restarted after a crash waited for it for ever (the demo stops the explorer
      // before its room visits; the scan mapper, started after it, was never restarted).
      if (!local->cmd->spec.oneshot && !local->want_running && local->state == ProcState::kStopped) continue;
      if (local->cmd->spec.oneshot ? !local->done : local->state != ProcState::kRunning) return false;
      continue;
    }
    // On another host: up while its heartbeats arrive.
    const auto it = std::find_if(seen_.begin(), seen_.end(), [&](const auto& s) { return s.first == d; });
    if (it == seen_.end() || now - it->second > options_.remote_fresh) return false;
  }
  return true;
}

bool Supervisor::dependents_alive(const Entry& e) const
{
  for (const auto& x : entries_) {
    if (x.pid == 0) continue;
    const auto& deps = x.cmd->spec.depends;
    if (std::find(deps.begin(), deps.end(), e.cmd->spec.name) != deps.end()) return true;
  }
  return false;
}

void Supervisor::spawn(Entry& e, Clock::time_point now)
{
  const auto& c = *e.cmd;
  SpawnRequest req{c.executable, c.argv, c.spec.env, lock_path(c.spec.name)};
  req.env.emplace_back("RGNAV_SUPERVISED", host_);
  const SpawnResult r = spawn_child(req);
  if (r.pid == 0) {
    // Our own child from an earlier life holding the lock: take it back rather than duplicate it.
    if (r.lock_holder != 0 && same_process_alive(r.lock_holder, r.lock_holder_start_ticks) &&
        read_cmdline(r.lock_holder) == c.argv) {
      adopt(e, r.lock_holder, r.lock_holder_start_ticks, now);
      save();
      return;
    }
    spdlog::error("{}: cannot start: {}", c.spec.name, r.error);
    if (r.lock_holder != 0) {
      // Someone else owns this process's devices; starting it again would make two owners.
      e.last_exit = r.error;
      e.want_running = false;
      set_state(e, ProcState::kFailed);
      raise_alert(c.spec.name + " not started on " + host_ + ": " + r.error);
      return;
    }
    e.started = now;
    failure(e, r.error, now);
    return;
  }
  spdlog::info("started {} (pid {}): {}", c.spec.name, r.pid, c.executable);
  e.pid = r.pid;
  e.start_ticks = r.start_ticks;
  e.adopted = false;
  e.started = now;
  e.last_heartbeat.reset();
  e.progress = -1;
  e.seq = -1;
  e.intent = StopIntent::kNone;
  e.killed = false;
  if (c.spec.heartbeat) {
    set_state(e, ProcState::kStarting);
  } else {
    running_again(e);
  }
  save();
}

void Supervisor::begin_stop(Entry& e, StopIntent intent, Clock::time_point now)
{
  if (e.pid == 0) return;
  release_silence(e);
  if (e.state == ProcState::kStopping || e.state == ProcState::kHung) {
    // Already on its way out; an operator stop during a restart must not restart it.
    if (intent == StopIntent::kOperator || intent == StopIntent::kShutdown) e.intent = intent;
    return;
  }
  const auto& spec = e.cmd->spec;
  e.intent = intent;
  e.killed = false;
  signal_child(e.pid, spec.stop_signal);
  auto grace = std::chrono::milliseconds(static_cast<int64_t>(spec.stop_time_allowed_s * 1000));
  if (intent == StopIntent::kHung) {
    spdlog::warn("{} (pid {}) is hung: {}; stopping it", spec.name, e.pid, e.hung_reason);
    // A stopped process cannot act on its stop signal until continued; a deadlocked one never
    // will: it gets a short grace, then SIGKILL.
    signal_child(e.pid, SIGCONT);
    grace = std::min(grace, options_.hung_grace);
    set_state(e, ProcState::kHung);
    if (e.safety_critical && !e.down_unplanned) spdlog::warn("robot held: safety-critical {} is hung", spec.name);
    e.down_unplanned = true;
  } else {
    set_state(e, ProcState::kStopping);
  }
  e.kill_at = now + grace;
}

void Supervisor::on_heartbeat(const std::string& name, pid_t pid, Clock::time_point now, bool same_machine,
                              int64_t progress, int64_t seq)
{
  auto it = std::find_if(seen_.begin(), seen_.end(), [&](const auto& s) { return s.first == name; });
  if (it == seen_.end()) {
    seen_.emplace_back(name, now);
  } else {
    it->second = now;
  }
  // A pid names a process on this machine only; another host's process may share it.
  Entry* e = same_machine ? find_pid(pid) : nullptr;
  if (!e) return;  // another host's process, a stale instance, or not ours
  if (name != e->cmd->spec.name && !e->name_warned) {
    spdlog::warn("{} (pid {}) calls itself \"{}\" in its heartbeats; matched by pid. Pass --name {} or set node.name "
                 "so other hosts can depend on it by name",
                 e->cmd->spec.name, pid, name, e->cmd->spec.name);
    e->name_warned = true;
  }
  const auto silent_ms = e->last_heartbeat ? std::chrono::duration_cast<std::chrono::milliseconds>(now - *e->last_heartbeat).count() : 0;
  e->last_heartbeat = now;
  // Its heartbeats are numbered: a jump means some were sent and never reached us (the bus or
  // our receive queue lost them), not that the process was silent.
  int64_t lost = 0;
  if (seq >= 0 && e->seq >= 0 && seq > e->seq + 1) lost = seq - e->seq - 1;
  if (seq > e->seq) e->seq = seq;
  heartbeats_lost_ += lost;
  if (lost >= 2 && !e->silence_held)
    spdlog::warn("{} (pid {}): {} heartbeats lost on the way to the supervisor ({} ms without one): the bus, not the process",
                 e->cmd->spec.name, pid, lost, silent_ms);
  if (e->silence_held) {
    // Back within the hold: its silence was the stall it shared, not its own.
    e->silence_held = false;
    if (const auto length = silence_.heard(now)) {
      ++stalls_.heard;
      count_stall(*length);
      const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(*length).count();
      if (lost > 0) {
        ++stalls_.heard_lost;
        spdlog::warn("host stalled for {} ms (heard, not felt: the heartbeats of {} stopped together and came back; {} "
                     "of {}'s were sent and lost on the way: the bus or the supervisor's receive queue): no process blamed",
                     ms, silence_.names(), lost, e->cmd->spec.name);
      } else {
        spdlog::warn("host stalled for {} ms (heard, not felt: the heartbeats of {} stopped together and came back): no "
                     "process blamed",
                     ms, silence_.names());
      }
    }
  }
  if (progress != e->progress) {
    e->progress = progress;
    e->progress_at = now;
    e->disk_wait_seen.reset();
  }
  if (e->state == ProcState::kStarting) running_again(*e);
}

bool Supervisor::waiting_on_disk(Entry& e, Clock::time_point now)
{
  if (now - e.progress_at > e.work_timeout + options_.disk_wait_timeout) return false;
  if (thread_state_(e.pid) == 'D') {
    // Logged once per stand-still: its first disk wait since it last moved on.
    if (!e.disk_wait_seen)
      spdlog::warn("{} (pid {}) has made no progress for {} ms, waiting on the disk: allowed {} ms more", e.cmd->spec.name,
                   e.pid, std::chrono::duration_cast<std::chrono::milliseconds>(now - e.progress_at).count(),
                   options_.disk_wait_timeout.count());
    e.disk_wait_seen = now;
  }
  return e.disk_wait_seen && now - *e.disk_wait_seen <= e.work_timeout;
}

void Supervisor::count_stall(Clock::duration length)
{
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(length);
  ++stalls_.count;
  stalls_.total += ms;
  stalls_.longest = std::max(stalls_.longest, ms);
  changed_ = true;
}

void Supervisor::judge_silence(Entry& e, Clock::time_point now)
{
  const auto ms = [](Clock::duration d) { return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count()); };
  const Clock::time_point last = *e.last_heartbeat;
  if (e.silence_held) {
    if (now - last <= e.heartbeat_timeout + options_.stall_hold) return;
    e.hung_reason = "heartbeat timeout (still silent " + ms(options_.stall_hold) + " ms past the bound, held for the silence of " +
                    silence_.names() + ")";
    begin_stop(e, StopIntent::kHung, now);
    return;
  }
  if (options_.stall_hold > Clock::duration::zero() && options_.stall_window > Clock::duration::zero()) {
    const auto window = silence_window(options_.stall_window, e.heartbeat_timeout);
    std::string with;
    Clock::time_point newest = last;
    for (const auto& x : entries_) {
      if (&x == &e || x.state != ProcState::kRunning || !x.cmd->spec.heartbeat || !x.last_heartbeat) continue;
      if (!began_together(*x.last_heartbeat, last, window)) continue;
      with += (with.empty() ? "" : ", ") + x.cmd->spec.name + " (silent " + ms(now - *x.last_heartbeat) + " ms)";
      newest = std::max(newest, *x.last_heartbeat);
    }
    if (!with.empty()) {
      e.silence_held = true;
      silence_.hold(e.cmd->spec.name, newest);
      spdlog::warn("{} (pid {}) silent {} ms, past its {} ms, together with {}: a stall of the host or the bus? verdict held "
                   "up to {} ms more",
                   e.cmd->spec.name, e.pid, ms(now - last), e.heartbeat_timeout.count(), with, options_.stall_hold.count());
      return;
    }
  }
  e.hung_reason = "heartbeat timeout";
  begin_stop(e, StopIntent::kHung, now);
}

void Supervisor::release_silence(Entry& e)
{
  if (!e.silence_held) return;
  e.silence_held = false;
  silence_.release();
}

void Supervisor::on_host_stall(Clock::duration gap, Clock::time_point now)
{
  if (gap <= Clock::duration::zero()) return;
  count_stall(gap);
  spdlog::warn("host stalled for {} ms (the supervisor's own tick was late): deadlines moved on by that much",
               std::chrono::duration_cast<std::chrono::milliseconds>(gap).count());
  // Every clock the hang checks read moves on by the gap, never past now.
  const auto later = [&](Clock::time_point t) { return std::min(t + gap, now); };
  for (auto& e : entries_) {
    if (e.last_heartbeat) e.last_heartbeat = later(*e.last_heartbeat);
    e.progress_at = later(e.progress_at);
    e.started = later(e.started);
  }
  for (auto& s : seen_) s.second = later(s.second);
  silence_.shift(gap, now);
}

void Supervisor::running_again(Entry& e)
{
  set_state(e, ProcState::kRunning);
  if (e.down_unplanned) {
    e.down_unplanned = false;
    changed_ = true;
  }
}

bool Supervisor::robot_held() const
{
  if (held_) return true;
  return std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.safety_critical && e.down_unplanned; });
}

void Supervisor::on_child_exit(pid_t pid, int wait_status, Clock::time_point now)
{
  Entry* e = find_pid(pid);
  if (!e) return;
  exited(*e, describe_wait_status(wait_status), now);
}

void Supervisor::reap(Clock::time_point now)
{
  int status = 0;
  pid_t pid;
  while ((pid = waitpid(-1, &status, WNOHANG)) > 0) on_child_exit(pid, status, now);
}

void Supervisor::exited(Entry& e, const std::string& how, Clock::time_point now)
{
  spdlog::info("{} (pid {}) ended: {}", e.cmd->spec.name, e.pid, how);
  cpu_.forget(e.pid);
  release_silence(e);
  e.pid = 0;
  e.start_ticks = 0;
  e.adopted = false;
  e.last_heartbeat.reset();
  e.progress = -1;
  e.seq = -1;
  const StopIntent intent = std::exchange(e.intent, StopIntent::kNone);
  save();
  switch (intent) {
    case StopIntent::kOperator:
    case StopIntent::kShutdown:
      e.last_exit = how;
      set_state(e, ProcState::kStopped);
      return;
    case StopIntent::kRestart:
      e.last_exit = how;
      set_state(e, ProcState::kStopped);  // want_running is set: tick() starts it again
      ++e.restarts;
      return;
    case StopIntent::kHung:
      failure(e, e.hung_reason + " (then " + how + ")", now);
      return;
    case StopIntent::kNone:
      if (e.cmd->spec.oneshot && how == "exit 0") {
        // A job that finished: done, not failed; dependents may go on.
        e.last_exit = "done (exit 0)";
        e.done = true;
        e.want_running = false;
        set_state(e, ProcState::kStopped);
        return;
      }
      failure(e, how, now);
      return;
  }
}

void Supervisor::failure(Entry& e, const std::string& reason, Clock::time_point now)
{
  e.last_exit = reason;
  const auto& name = e.cmd->spec.name;
  if (!e.want_running || shutting_down_) {
    e.down_unplanned = false;
    set_state(e, ProcState::kStopped);
    return;
  }
  if (e.safety_critical && !e.down_unplanned) spdlog::warn("robot held: safety-critical {} is down ({})", name, reason);
  if (!e.down_unplanned) changed_ = true;
  e.down_unplanned = true;
  if (!e.auto_respawn) {
    e.want_running = false;
    e.down_unplanned = false;
    set_state(e, ProcState::kStopped);
    raise_alert(name + " on " + host_ + " stopped (" + reason + "); auto_respawn is off");
    return;
  }
  const auto d = e.policy.on_failure(now, e.started);
  if (d.give_up) {
    e.want_running = false;
    set_state(e, ProcState::kFailed);
    raise_alert(name + " on " + host_ + " FAILED: already restarted " + std::to_string(options_.restart.max_restarts) +
                " times within " + std::to_string(options_.restart.window.count() / 1000.0).substr(0, 4) + " s; last: " + reason);
    if (e.safety_critical && !held_) {
      held_ = true;
      raise_alert("robot stopped and held: safety-critical " + name + " failed");
    }
    return;
  }
  e.restart_at = now + d.delay;
  set_state(e, ProcState::kBackoff);
}

void Supervisor::tick(Clock::time_point now)
{
  // Adopted children are not ours to waitpid: /proc tells whether they still live.
  if (now - last_adopted_check_ >= std::chrono::milliseconds(20)) {
    last_adopted_check_ = now;
    for (auto& e : entries_) {
      if (e.adopted && e.pid != 0 && !same_process_alive(e.pid, e.start_ticks))
        exited(e, "exited (adopted: status unknown)", now);
    }
    for (auto it = orphans_.begin(); it != orphans_.end();) {
      if (!same_process_alive(it->pid, it->start_ticks)) {
        it = orphans_.erase(it);
        save();
        continue;
      }
      if (!it->killed && now >= it->kill_at) {
        signal_child(it->pid, SIGKILL);
        it->killed = true;
      }
      ++it;
    }
  }

  for (auto& e : entries_) {
    switch (e.state) {
      case ProcState::kStarting:
        if (now - e.started > (e.adopted ? 2 * e.heartbeat_timeout : e.startup_timeout)) {
          e.hung_reason = "no heartbeat within " + std::to_string((e.adopted ? 2 * e.heartbeat_timeout : e.startup_timeout).count()) + " ms of start";
          begin_stop(e, StopIntent::kHung, now);
        }
        break;
      case ProcState::kRunning:
        if (e.cmd->spec.heartbeat && e.last_heartbeat && now - *e.last_heartbeat > e.heartbeat_timeout) {
          // Silent: hung, or held while its silence is shared (no progress comes without heartbeats either).
          judge_silence(e, now);
        } else if (e.cmd->spec.heartbeat && e.progress > 0 && now - e.progress_at > e.work_timeout &&
                   !waiting_on_disk(e, now)) {
          // Heartbeats come (beside the loop) but the loop has not moved on: stuck in its work.
          e.hung_reason = "no progress for " + std::to_string(e.work_timeout.count()) + " ms while beating";
          begin_stop(e, StopIntent::kHung, now);
        } else if (e.cmd->spec.heartbeat && e.progress <= 0 && now - e.started > e.startup_timeout) {
          // Beating from its first moments, but its loop never turned: stuck in its start-up.
          e.hung_reason = "no progress within " + std::to_string(e.startup_timeout.count()) + " ms of start";
          begin_stop(e, StopIntent::kHung, now);
        }
        break;
      case ProcState::kStopping:
      case ProcState::kHung:
        if (!e.killed && now >= e.kill_at) {
          spdlog::warn("{} (pid {}) did not stop in time: SIGKILL", e.cmd->spec.name, e.pid);
          signal_child(e.pid, SIGKILL);
          e.killed = true;
        }
        break;
      case ProcState::kBackoff:
        if (!e.want_running) {
          set_state(e, ProcState::kStopped);
        } else if (now >= e.restart_at && dependencies_up(e, now)) {
          ++e.restarts;
          spawn(e, now);
        }
        break;
      case ProcState::kStopped:
        if (e.want_running && !e.missing && !shutting_down_ && dependencies_up(e, now)) spawn(e, now);
        break;
      case ProcState::kFailed:
        break;
    }
  }

  if (shutting_down_) {
    // Dependents first: a process is stopped once nothing that needs it is still alive.
    for (auto it = entries_.rbegin(); it != entries_.rend(); ++it) {
      if (it->pid != 0 && it->state != ProcState::kStopping && it->state != ProcState::kHung && !dependents_alive(*it))
        begin_stop(*it, StopIntent::kShutdown, now);
    }
  }

  if (held_) {
    bool all_up = true;
    for (const auto& e : entries_)
      if (e.safety_critical && !e.missing && e.state != ProcState::kRunning) all_up = false;
    if (all_up && !shutting_down_) {
      held_ = false;
      raise_alert("robot hold released: safety-critical processes running again");
    }
  }
}

std::vector<ProcessView> Supervisor::status(Clock::time_point now)
{
  std::vector<ProcessView> out;
  for (const auto& e : entries_) {
    ProcessView v;
    v.name = e.cmd->spec.name;
    v.group = e.cmd->spec.group;
    v.state = e.state;
    v.pid = e.pid;
    v.restarts = e.restarts;
    v.last_exit = e.last_exit;
    v.adopted = e.adopted;
    if (e.last_heartbeat) v.heartbeat_age_us = std::chrono::duration_cast<std::chrono::microseconds>(now - *e.last_heartbeat).count();
    if (e.pid != 0) {
      if (const auto st = read_proc_stat(e.pid)) v.cpu_percent = cpu_.sample(e.pid, st->cpu_ticks, now);
      v.rss_kb = read_rss_kb(e.pid);
    }
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace rgnav::supervisor
