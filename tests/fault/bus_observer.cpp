#include "bus_observer.h"

#include <cmath>

#include "bus/typed.h"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/explorer_status_t.hpp"
#include "rgnav/global_path_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "time/message_time.h"

namespace rgnav::fault {

namespace {

// When a drive-chain message was made, on the harness's steady clock: its utime (wall time on
// this host: commands, odometry, the simulator's real-time clock) mapped back from the age it has
// now, so a harness that was not scheduled for a while does not see old samples as new ones.
// Arrival time where utime is no recent wall time.
Clock::time_point made_at(int64_t utime, int64_t max_age_us = 2'000'000)
{
  const auto now = Clock::now();
  const int64_t age = time::wall_utime() - utime;
  if (age < 0 || age > max_age_us) return now;
  return now - std::chrono::microseconds(age);
}

// A heartbeat's utime is always the wall time of sending (heartbeat_t): any age under a minute
// is the time it waited to be read.
constexpr int64_t kHeartbeatMaxAgeUs = 60'000'000;

}  // namespace

BusObserver::BusObserver(const std::string& url, const std::string& host, const std::vector<std::string>& input_channels,
                         const std::map<std::string, std::string>& state_channels, const Channels& channels)
    : bus_(url), host_(host)
{
  bus::subscribe<heartbeat_t>(
      bus_, "HEARTBEAT",
      [this](const heartbeat_t& hb, const bus::RawMessage&) {
        const auto now = Clock::now();
        const auto sent = made_at(hb.utime, kHeartbeatMaxAgeUs);
        auto& t = hb_[hb.name];
        t.max_late = std::max(t.max_late, std::chrono::duration_cast<std::chrono::milliseconds>(now - sent));
        const bool same_process = t.pid == hb.pid && t.last != Clock::time_point{};
        if (same_process) {
          t.max_gap = std::max(t.max_gap, std::chrono::duration_cast<std::chrono::milliseconds>(sent - t.last));
          if (hb.seq > t.seq + 1) t.lost += hb.seq - t.seq - 1;
        }
        t.seq = hb.seq;
        t.pid = hb.pid;
        t.last = same_process ? std::max(t.last, sent) : sent;
        t.dropped = hb.messages_dropped;
        t.messages_in = hb.messages_in;
        t.busy_ms = hb.busy_ms;
        hb_log_.push_back({now, hb.name, hb.pid, hb.messages_in, hb.progress});
      },
      &drops_);
  bus::subscribe<supervisor_status_t>(
      bus_, "SUPERVISOR_STATUS",
      [this](const supervisor_status_t& s, const bus::RawMessage&) {
        if (s.host != host_) return;
        const auto now = Clock::now();
        last_status_ = s;
        have_status_ = true;
        last_status_time_ = now;
        for (const auto& p : s.processes) status_log_.push_back({now, p});
      },
      &drops_);
  for (const auto& [process, channel] : state_channels) {
    state_channel_of_[channel] = process;
    bus::subscribe<velocity_cmd_t>(
        bus_, channel,
        [this, process = process](const velocity_cmd_t& m, const bus::RawMessage&) {
          state_log_[process].push_back({Clock::now(), m.seq});
        },
        &drops_);
  }
  for (const auto& ch : input_channels) {
    bus_.subscribe(ch, [this](const bus::RawMessage& m) {
      // Keep a valid copy: flood material must be what the process normally reads.
      if (capture_inputs_ && m.size >= 8) inputs_[m.channel].assign(m.data, m.data + m.size);
    });
  }
  bus::subscribe<velocity_cmd_t>(
      bus_, channels.base_cmd,
      [this](const velocity_cmd_t& m, const bus::RawMessage&) {
        cmd_log_.push_back({made_at(m.utime), m.v, m.omega, m.source == "supervisor", m.deadline_us});
      },
      &drops_);
  bus::subscribe<odometry_t>(
      bus_, channels.drive_odometry,
      [this](const odometry_t& m, const bus::RawMessage&) {
        drive_log_.push_back({made_at(m.utime), m.v, m.omega, false, 0, m.status == odometry_t::STATUS_FAULT});
      },
      &drops_);
  if (!channels.truth.empty()) {
    has_truth_ = true;
    bus::subscribe<odometry_t>(
        bus_, channels.truth,
        [this](const odometry_t& m, const bus::RawMessage&) { truth_log_.push_back({made_at(m.utime), m.v, m.omega, false, 0}); },
        &drops_);
  }
  bus::subscribe<rg_map_t>(
      bus_, channels.rg_map,
      [this](const rg_map_t& m, const bus::RawMessage&) {
        MapSample s{Clock::now(), m.version, m.last_scan_id, {}, {}};
        for (const auto& r : m.regions) s.region_ids.push_back(r.id);
        for (const auto& g : m.gateways) s.gateway_ids.push_back(g.id);
        map_log_.push_back(std::move(s));
      },
      &drops_);
  bus::subscribe<aligned_scan_t>(
      bus_, channels.aligned_scan,
      [this](const aligned_scan_t& m, const bus::RawMessage&) { aligned_log_.push_back({Clock::now(), m.scan_id, m.revision}); },
      &drops_);
  bus::subscribe<global_path_t>(
      bus_, channels.global_path,
      [this](const global_path_t& m, const bus::RawMessage&) { path_log_.push_back({Clock::now(), m.goal_id, m.status}); },
      &drops_);
  bus::subscribe<explorer_status_t>(
      bus_, channels.explorer_status,
      [this](const explorer_status_t& m, const bus::RawMessage&) {
        explorer_log_.push_back({Clock::now(), m.phase, int64_t{m.stack_pending} + m.stack_done + m.stack_set_aside, m.goals_sent});
      },
      &drops_);
}

void BusObserver::spin(std::chrono::milliseconds d)
{
  const auto until = Clock::now() + d;
  while (Clock::now() < until)
    bus_.handle(std::max(std::chrono::milliseconds(1), std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now())));
}

bool BusObserver::wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout)
{
  const auto until = Clock::now() + timeout;
  while (!pred()) {
    if (Clock::now() >= until) return false;
    bus_.handle(std::chrono::milliseconds(5));
  }
  return true;
}

const HeartbeatTrack* BusObserver::heartbeat(const std::string& name) const
{
  const auto it = hb_.find(name);
  return it == hb_.end() ? nullptr : &it->second;
}

void BusObserver::reset_gaps()
{
  for (auto& [n, t] : hb_) {
    t.max_gap = std::chrono::milliseconds(0);
    t.max_late = std::chrono::milliseconds(0);
    t.lost = 0;
  }
}

std::chrono::milliseconds BusObserver::max_late() const
{
  std::chrono::milliseconds worst{0};
  for (const auto& [n, t] : hb_) worst = std::max(worst, t.max_late);
  return worst;
}

std::chrono::milliseconds BusObserver::gap_now(const std::string& name) const
{
  const auto* t = heartbeat(name);
  if (!t) return std::chrono::milliseconds(-1);
  return std::max(t->max_gap, std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t->last));
}

std::optional<process_status_t> BusObserver::status(const std::string& name) const
{
  if (!have_status_) return std::nullopt;
  for (const auto& p : last_status_.processes)
    if (p.name == name) return p;
  return std::nullopt;
}

std::optional<Clock::time_point> BusObserver::first_status(const std::string& name, Clock::time_point t,
                                                           const std::function<bool(const process_status_t&)>& pred) const
{
  for (const auto& s : status_log_)
    if (s.when >= t && s.p.name == name && pred(s.p)) return s.when;
  return std::nullopt;
}

std::optional<Clock::time_point> BusObserver::first_heartbeat_new_pid(const std::string& name, int old_pid, Clock::time_point t) const
{
  for (const auto& h : hb_log_)
    if (h.when >= t && h.name == name && h.pid != old_pid) return h.when;
  return std::nullopt;
}

std::optional<Clock::time_point> BusObserver::first_heartbeat_with_input(const std::string& name, int pid, Clock::time_point t) const
{
  for (const auto& h : hb_log_)
    if (h.when >= t && h.name == name && h.pid == pid && h.messages_in > 0) return h.when;
  return std::nullopt;
}

std::optional<Clock::time_point> BusObserver::last_seen_progressing(const std::string& name, int pid, Clock::time_point from,
                                                                   Clock::time_point to) const
{
  std::vector<const HeartbeatSample*> window;
  for (const auto& h : hb_log_)
    if (h.when >= from && h.when <= to && h.name == name && h.pid == pid) window.push_back(&h);
  if (window.empty()) return std::nullopt;
  const int64_t frozen = window.back()->progress;
  for (auto it = window.rbegin(); it != window.rend(); ++it)
    if ((*it)->progress != frozen) return (*it)->when;
  return std::nullopt;
}

std::string BusObserver::heartbeat_trace(const std::string& name, int pid, Clock::time_point from, Clock::time_point to,
                                         Clock::time_point t0) const
{
  std::string out;
  std::optional<int64_t> before;
  for (const auto& h : hb_log_) {
    if (h.name != name || h.pid != pid || h.when > to) continue;
    if (h.when >= from) {
      const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(h.when - t0).count();
      out += (out.empty() ? "" : " ") + std::to_string(ms) + ":+" + (before ? std::to_string(h.progress - *before) : "?");
    }
    before = h.progress;
  }
  return out;
}

std::optional<int64_t> BusObserver::state(const std::string& name) const
{
  const auto it = state_log_.find(name);
  if (it == state_log_.end() || it->second.empty()) return std::nullopt;
  return it->second.back().second;
}

std::optional<int64_t> BusObserver::first_state_since(const std::string& name, Clock::time_point t) const
{
  const auto it = state_log_.find(name);
  if (it == state_log_.end()) return std::nullopt;
  for (const auto& [when, v] : it->second)
    if (when >= t) return v;
  return std::nullopt;
}

const std::vector<uint8_t>* BusObserver::captured_input(const std::string& channel) const
{
  const auto it = inputs_.find(channel);
  return it == inputs_.end() ? nullptr : &it->second;
}

}  // namespace rgnav::fault
