#include "supervisor_node.h"

#include <unistd.h>

#include <algorithm>
#include <spdlog/spdlog.h>

#include "order_conversions.h"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/supervisor_status_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "time/message_time.h"

namespace rgnav::supervisor {

SupervisorNode::SupervisorNode(runtime::Node& node, std::unique_ptr<Supervisor> supervisor, SupervisorOptions options,
                               SupervisorChannels channels, OrderGate orders)
    : node_(node), sup_(std::move(supervisor)), options_(std::move(options)), channels_(std::move(channels)),
      orders_(std::move(orders))
{
  // Heartbeats carry the sender's hostname(2): only those of this machine have pids of ours.
  char buf[256] = {0};
  gethostname(buf, sizeof buf - 1);
  hostname_ = buf;
  node_.subscribe<heartbeat_t>(channels_.heartbeat, [this](const heartbeat_t& hb) {
    sup_->on_heartbeat(hb.name, hb.pid, Clock::now(), hb.host == hostname_, hb.progress, hb.seq);
  });
  node_.subscribe<supervisor_order_t>(channels_.orders, [this](const supervisor_order_t& o) {
    if (!o.host.empty() && o.host != sup_->host()) return;
    // Unsigned, forged, stale and replayed orders are refused (and reported); copies of one
    // already carried out are dropped.
    const OrderDecision d = orders_.on_order(to_order_fields(o), time::wall_utime(), Clock::now());
    if (!d.log.empty()) spdlog::warn("{}", d.log);
    if (!d.alert.empty()) sup_->note_alert(d.alert);
    if (!d.execute) return;
    static const char* names[] = {"?", "start", "stop", "restart", "shutdown"};
    spdlog::info("order {} {} \"{}\" from {}", o.order_id, names[o.order >= 1 && o.order <= 4 ? o.order : 0], o.target,
                 printable_source(o.source));
    std::string why;
    if (!sup_->order(static_cast<Order>(o.order), o.target, Clock::now(), &why)) {
      // Broadcast orders name processes of other hosts too; only a named host's miss is news.
      if (!o.host.empty()) spdlog::warn("order {}: {}", o.order_id, why);
    }
  });
  node_.every(options_.tick, [this] { on_tick(); });
  node_.every(options_.status_period, [this] { publish_status(); });
  node_.every(std::chrono::microseconds(static_cast<int64_t>(1e6 / options_.hold_hz)), [this] { publish_hold(); });
  node_.set_status(heartbeat_t::STATE_RUNNING, "supervising " + std::to_string(sup_->plan().commands.size()) + " commands on " + sup_->host());
}

SupervisorNode::~SupervisorNode()
{
  try {
    drain();
  } catch (const std::exception& e) {
    spdlog::error("while stopping children: {}", e.what());
  }
}

void SupervisorNode::on_tick()
{
  const auto now = Clock::now();
  // The tick is due every options_.tick: later than that by more than the threshold, the
  // whole host (the supervisor with it) was not running, and the processes' silence in that
  // gap is not theirs.
  if (last_tick_ != Clock::time_point{}) {
    const auto late = now - last_tick_ - options_.tick;
    if (late > options_.stall_threshold) sup_->on_host_stall(late, now);
  }
  last_tick_ = now;
  sup_->reap(now);
  sup_->tick(now);
  if (sup_->shutting_down() && sup_->finished()) node_.request_stop();
  if (sup_->take_changed() && now - last_status_ >= options_.status_min_gap) publish_status();
}

void SupervisorNode::publish_status()
{
  const auto now = Clock::now();
  last_status_ = now;
  supervisor_status_t s;
  s.utime = time::wall_utime();
  s.host = sup_->host();
  s.config = sup_->plan().config.file;
  for (const auto& v : sup_->status(now)) {
    process_status_t p;
    p.name = v.name;
    p.group = v.group;
    p.state = static_cast<int8_t>(v.state);
    p.pid = v.pid;
    p.restarts = v.restarts;
    p.last_exit = v.last_exit + (v.adopted ? " [adopted]" : "");
    p.heartbeat_age_us = v.heartbeat_age_us;
    p.cpu_percent = v.cpu_percent;
    p.rss_kb = v.rss_kb;
    s.processes.push_back(std::move(p));
  }
  s.nprocesses = static_cast<int32_t>(s.processes.size());
  s.robot_held = sup_->robot_held();
  s.alert = sup_->alert();
  const auto& stalls = sup_->host_stalls();
  s.host_stalls = stalls.count;
  s.host_stall_max_ms = static_cast<int32_t>(stalls.longest.count());
  s.host_stall_total_ms = stalls.total.count();
  node_.publish(channels_.status, s);
}

void SupervisorNode::publish_hold()
{
  if (!sup_->robot_held()) return;
  velocity_cmd_t cmd;
  cmd.utime = time::wall_utime();
  cmd.seq = ++hold_seq_;
  cmd.v = 0;
  cmd.omega = 0;
  cmd.deadline_us = static_cast<int32_t>(std::chrono::duration_cast<std::chrono::microseconds>(options_.hold_deadline).count());
  cmd.source = "supervisor";
  node_.publish(channels_.base_cmd, cmd);
}

void SupervisorNode::drain()
{
  // The node's loop has ended (signal or shutdown order); keep reaping and publishing status
  // until the children are gone. Stop signals, grace periods and SIGKILL bound this.
  sup_->shutdown(Clock::now());
  auto next_status = Clock::now();
  while (!sup_->finished()) {
    node_.bus().handle(options_.tick);
    const auto now = Clock::now();
    sup_->reap(now);
    sup_->tick(now);
    publish_hold();
    if (sup_->take_changed() || now >= next_status) {
      publish_status();
      next_status = now + options_.status_period;
    }
  }
  publish_status();
  spdlog::info("all processes stopped");
}

}  // namespace rgnav::supervisor
