#include "runtime/node.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <csignal>
#include <stdexcept>

#include "bus/lcm_bus.h"
#include "rgnav/heartbeat_t.hpp"
#include "runtime/fault_injection.h"
#include "runtime/realtime.h"

namespace rgnav::runtime {

NodeOptions load_node_options(const config::Config& node_section, const std::string& default_name)
{
  NodeOptions o;
  o.name = node_section.string("name", default_name);
  if (o.name.empty()) node_section.fail("name", "must not be empty");
  o.lcm_url = node_section.string("lcm_url", "");
  o.heartbeat_channel = node_section.string("heartbeat_channel", o.heartbeat_channel);
  o.heartbeat_hz = node_section.number("heartbeat_hz", o.heartbeat_hz, 0.5, 100.0);
  o.input_stale_after = std::chrono::milliseconds(
      node_section.integer("input_stale_after_ms", o.input_stale_after.count(), 0, 3'600'000));
  o.max_stamp_jump = std::chrono::milliseconds(node_section.integer("max_stamp_jump_ms", o.max_stamp_jump.count(), 100, 3'600'000));
  o.realtime_priority = static_cast<int>(node_section.integer("realtime_priority", o.realtime_priority, 0, 99));
  return o;
}

namespace {

std::string host_name()
{
  char buf[256] = {0};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

std::chrono::microseconds heartbeat_period(const NodeOptions& o)
{
  return std::chrono::microseconds(static_cast<int64_t>(1e6 / o.heartbeat_hz));
}

int64_t steady_ns(Node::Clock::time_point t)
{
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

}  // namespace

Node::Node(NodeOptions options)
    : options_(std::move(options)), signals_(std::make_unique<SignalWatcher>()), clock_(options_.max_stamp_jump)
{
  if (options_.realtime_priority > 0) {
    // Before the bus: LCM's receive thread and the heartbeat thread inherit it (LCM 1.3 reads the
    // socket in a thread of its own, which at normal priority held ODOMETRY back under load).
    request_realtime_logged("event loop and LCM threads", options_.realtime_priority, false,
                            "messages may come late under load");
  }
  bus_ = std::make_unique<bus::LcmBus>(options_.lcm_url);
  host_ = host_name();
  attach_fault_injection(*bus_, options_.name);  // only under the fault harness (fault_injection.h)
  every(heartbeat_period(options_), [this] {
    if (!beat_beside_loop_) publish_heartbeat();
  });
  // From here on: the process's own start-up (a journal replayed, a map loaded) is beaten
  // through, and bounded by its progress like any other long work.
  start_heartbeat_thread();
}

Node::Node(NodeOptions options, std::unique_ptr<bus::Bus> bus)
    : options_(std::move(options)),
      signals_(std::make_unique<SignalWatcher>()),
      bus_(std::move(bus)),
      clock_(options_.max_stamp_jump)
{
  host_ = host_name();
  every(heartbeat_period(options_), [this] {
    if (!beat_beside_loop_) publish_heartbeat();
  });
}

Node::~Node() { stop_heartbeat_thread(); }

void Node::every(std::chrono::microseconds period, std::function<void()> fn)
{
  const auto p = std::chrono::duration_cast<Clock::duration>(period);
  wall_timers_.push_back({p, Clock::now() + p, std::move(fn)});
}

void Node::every_message_time(time::Duration period, std::function<void(time::Time)> fn)
{
  message_timers_.push_back({period, false, {}, std::move(fn)});
}

void Node::watch_fd(std::function<int()> fd, std::function<void()> on_ready)
{
  if (fd_watches_.size() >= kMaxFdWatches) throw std::logic_error("Node::watch_fd: more than 8 descriptors");
  fd_watches_.push_back({std::move(fd), std::move(on_ready)});
}

void Node::on_input(int64_t utime)
{
  {
    const std::lock_guard<std::mutex> lock(state_mutex_);
    has_input_ = true;
    last_input_ = Clock::now();
    ++messages_in_;
  }
  if (!clock_.observe(time::from_utime(utime))) return;
  const time::Time now = clock_.now();
  for (auto& t : message_timers_) {
    if (!t.started) {
      // Align to multiples of the period so replays of the same log fire at the same times.
      const auto ticks = now.time_since_epoch() / t.period;
      t.next = time::Time((ticks + 1) * t.period);
      t.started = true;
      continue;
    }
    if (now < t.next) continue;
    const auto ticks = now.time_since_epoch() / t.period;
    t.next = time::Time((ticks + 1) * t.period);
    t.fn(now);
  }
}

void Node::set_status(int8_t state, const std::string& text)
{
  const std::lock_guard<std::mutex> lock(state_mutex_);
  status_override_ = true;
  override_state_ = state;
  override_text_ = text;
}

void Node::clear_status()
{
  const std::lock_guard<std::mutex> lock(state_mutex_);
  status_override_ = false;
}

void Node::publish_heartbeat()
{
  {
    const std::lock_guard<std::mutex> lock(state_mutex_);
    dropped_seen_ = drops_.total();
  }
  send_heartbeat();
}

void Node::send_heartbeat()
{
  // One sender at a time, so sequence numbers go out in order whichever thread sends; the state
  // lock is not held while publishing (a synchronous bus delivers to this node's own handlers).
  const std::lock_guard<std::mutex> sending(send_mutex_);
  heartbeat_t hb;
  hb.utime = time::wall_utime();
  hb.name = options_.name;
  hb.host = host_;
  hb.pid = static_cast<int32_t>(getpid());
  const auto now = Clock::now();
  hb.progress = progress_.load(std::memory_order_relaxed);
  const int64_t busy_since = busy_since_ns_.load(std::memory_order_relaxed);
  hb.busy_ms = busy_since == 0 ? 0 : static_cast<int32_t>(std::max<int64_t>(0, (steady_ns(now) - busy_since) / 1'000'000));
  hb.rss_kb = ProcStats::rss_kb();
  std::unique_lock<std::mutex> lock(state_mutex_);
  hb.seq = ++heartbeat_seq_;
  hb.last_input_age_us =
      has_input_ ? std::chrono::duration_cast<std::chrono::microseconds>(now - last_input_).count() : -1;
  hb.cpu_percent = stats_.cpu_percent();
  hb.messages_in = messages_in_;
  hb.messages_dropped = dropped_seen_;
  if (stop_requested_) {
    hb.state = heartbeat_t::STATE_STOPPING;
    hb.status = "stopping";
  } else if (status_override_) {
    hb.state = override_state_;
    hb.status = override_text_;
  } else if (has_subscriptions_ && !has_input_) {
    hb.state = heartbeat_t::STATE_STARTING;
    hb.status = "waiting for input";
  } else if (has_subscriptions_ && options_.input_stale_after.count() > 0 &&
             now - last_input_ > options_.input_stale_after) {
    hb.state = heartbeat_t::STATE_DEGRADED;
    hb.status = "inputs stale";
  } else {
    hb.state = heartbeat_t::STATE_RUNNING;
    hb.status = "ok";
  }
  lock.unlock();
  bus::publish(*bus_, options_.heartbeat_channel, hb);
}

void Node::heartbeat_loop()
{
  const auto period = std::chrono::duration_cast<Clock::duration>(heartbeat_period(options_));
  std::unique_lock<std::mutex> lock(beat_mutex_);
  auto next = Clock::now() + period;
  while (!beat_wake_.wait_until(lock, next, [this] { return beat_stop_; })) {
    lock.unlock();
    send_heartbeat();
    lock.lock();
    // Missed beats (the host stalled) are skipped, not sent in a burst.
    const auto now = Clock::now();
    next += period * (1 + std::max<Clock::rep>(0, (now - next) / period));
  }
}

void Node::start_heartbeat_thread()
{
  if (!bus_->thread_safe_publish() || beat_thread_.joinable()) return;
  beat_stop_ = false;
  beat_thread_ = std::thread([this] { heartbeat_loop(); });
  beat_beside_loop_ = true;
}

void Node::stop_heartbeat_thread()
{
  if (!beat_thread_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(beat_mutex_);
    beat_stop_ = true;
  }
  beat_wake_.notify_all();
  beat_thread_.join();
  beat_beside_loop_ = false;
}

void Node::run_due_timers()
{
  const auto now = Clock::now();
  // Index loop: a timer callback may register further timers.
  for (size_t i = 0; i < wall_timers_.size(); ++i) {
    if (now < wall_timers_[i].next) continue;
    // Skip missed periods instead of bursting to catch up (a stalled process stays sane).
    const auto period = wall_timers_[i].period;
    wall_timers_[i].next += period * (1 + (now - wall_timers_[i].next) / period);
    auto fn = wall_timers_[i].fn;
    fn();
  }
}

Node::Clock::time_point Node::next_deadline() const
{
  auto next = Clock::time_point::max();
  for (const auto& t : wall_timers_) next = std::min(next, t.next);
  return next;
}

bool Node::spin_once(std::chrono::milliseconds max_wait)
{
  if (stop_requested_) return false;
  const auto now = Clock::now();
  auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_deadline() - now);
  wait = std::clamp(wait, std::chrono::milliseconds(0), max_wait);

  pollfd fds[2 + kMaxFdWatches] = {{signals_->fd(), POLLIN, 0}, {bus_->fileno(), POLLIN, 0}};
  const int nfds = fds[1].fd >= 0 ? 2 : 1;
  // Watched descriptors follow; fds[1] stays the bus slot even when unused.
  size_t watched = 0;
  for (; watched < fd_watches_.size(); ++watched)
    fds[2 + watched] = {fd_watches_[watched].fd(), POLLIN, 0};  // poll ignores fd -1
  if (nfds == 1) fds[1].fd = -1;
  const nfds_t total = watched > 0 ? static_cast<nfds_t>(2 + watched) : static_cast<nfds_t>(nfds);
  busy_since_ns_.store(0, std::memory_order_relaxed);
  const int r = poll(fds, total, static_cast<int>(wait.count()));
  busy_since_ns_.store(steady_ns(Clock::now()), std::memory_order_relaxed);
  note_progress();
  if (r > 0 && (fds[0].revents & POLLIN)) {
    const int sig = signals_->take();
    if (sig != 0) {
      spdlog::info("received signal {}, stopping", sig);
      stop_requested_ = true;
      publish_heartbeat();  // tell the supervisor this exit is intended
      return false;
    }
  }
  if (nfds == 2 && r > 0 && (fds[1].revents & (POLLIN | POLLERR | POLLHUP))) {
    if (bus_->handle(std::chrono::milliseconds(0)) < 0) {
      spdlog::error("bus error on {}", bus_->url());
      bus_failed_ = true;
      stop_requested_ = true;
      return false;
    }
  } else if (nfds == 1) {
    bus_->handle(std::chrono::milliseconds(0));
  }
  for (size_t i = 0; r > 0 && i < watched; ++i)
    if (fds[2 + i].fd >= 0 && (fds[2 + i].revents & (POLLIN | POLLERR | POLLHUP | POLLNVAL)))
      fd_watches_[i].on_ready();
  {
    // For the heartbeat beside the loop (the drop counter is the loop's alone).
    const std::lock_guard<std::mutex> lock(state_mutex_);
    dropped_seen_ = drops_.total();
  }
  run_due_timers();
  return !stop_requested_;
}

int Node::run()
{
  spdlog::info("{} running on {}", options_.name, bus_->url());
  publish_heartbeat();
  start_heartbeat_thread();
  while (!stop_requested_) spin_once(std::chrono::milliseconds(100));
  stop_heartbeat_thread();
  spdlog::info("{} stopped ({} inputs, {} dropped)", options_.name, messages_in_, drops_.total());
  return bus_failed_ ? 1 : 0;
}

}  // namespace rgnav::runtime
