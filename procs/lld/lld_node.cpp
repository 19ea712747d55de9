#include "lld/lld_node.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "msg/conversions.h"
#include "runtime/realtime.h"
#include "rgnav/heartbeat_t.hpp"
#include "trajectory/trajectory_conversions.h"

namespace rgnav::lld {

namespace {

const char* reason_text(StopReason r)
{
  switch (r) {
    case StopReason::kStaleOdometry: return "stale odometry";
    case StopReason::kStaleTrajectory: return "stale trajectory";
    case StopReason::kCancelled: return "cancelled";
    case StopReason::kEndOfPlan: return "end of plan";
    case StopReason::kLoopGap: return "control loop held up past its bounds";
    default: return "";
  }
}

}  // namespace

LldNode::LldNode(runtime::Node& node, const LldOptions& options, bool start_thread)
    : node_(node),
      options_(options),
      follower_(options.follower),
      stall_credit_(options.stall_excuse_max_s),
      loop_(std::chrono::nanoseconds(static_cast<int64_t>(1e9 / options.loop.rate_hz)))
{
  cmd_msg_.source = node_.name();
  cmd_msg_.deadline_us = options_.loop.command_deadline_ms * 1000;
  cmd_buf_.resize(static_cast<size_t>(cmd_msg_.getEncodedSize()) + 64);
  status_buf_.resize(static_cast<size_t>(status_msg_.getEncodedSize()) + 64);

  node_.subscribe<trajectory_t>(options_.channels.trajectory, [this](const trajectory_t& m) { on_trajectory(m); });
  node_.subscribe<odometry_t>(options_.channels.odometry, [this](const odometry_t& m) { on_odometry(m); });
  node_.every(std::chrono::milliseconds(200), [this] { update_heartbeat(); });
  if (start_thread) thread_ = std::thread([this] { control_thread(); });
}

void LldNode::stop_loop()
{
  loop_.stop();
  if (thread_.joinable()) thread_.join();
}

LldNode::~LldNode()
{
  stop_loop();
  const LoopStats s = loop_.stats();
  if (s.ticks > 0)
    spdlog::info("control loop: {} ticks, {} overruns, period jitter p50 {:.3f} ms p99 {:.3f} ms max {:.3f} ms",
                 s.ticks, s.overruns, s.jitter_p50_ms, s.jitter_p99_ms, s.jitter_max_ms);
}

void LldNode::on_trajectory(const trajectory_t& msg)
{
  std::unique_ptr<Plan> retired, superseded;
  if (msg.trajectory_id == last_trajectory_id_ && msg.nsegments > 0) {
    // The sender re-sent the trajectory it still wants: keep following, no re-plan.
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    if (!take_stamp(msg.utime, options_.channels.trajectory)) return;
    inbox_.refresh_id = msg.trajectory_id;
    inbox_.has_refresh = true;
    retired = std::move(inbox_.retired);
    return;
  }
  std::string why;
  auto t = trajectory::from_msg(msg, &why);
  if (!t) {
    node_.drops().drop(options_.channels.trajectory, why);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    if (!take_stamp(msg.utime, options_.channels.trajectory)) return;
  }
  last_trajectory_id_ = msg.trajectory_id;
  auto plan = make_plan(std::move(*t), options_.follower, v_command_.load());
  if (!plan->profile.feasible())
    spdlog::warn("trajectory {}: cannot meet its first speed limits from {:.2f} m/s; braking at a_max",
                 msg.trajectory_id, v_command_.load());
  {
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    superseded = std::move(inbox_.pending);  // never taken by the loop
    retired = std::move(inbox_.retired);
    inbox_.pending = std::move(plan);
  }
  // Both are freed here, in the Node's thread, after the lock.
}

void LldNode::on_odometry(const odometry_t& msg)
{
  std::lock_guard<std::mutex> lock(inbox_mutex_);
  if (!take_stamp(msg.utime, options_.channels.odometry)) return;
  inbox_.odometry.pose = msg::to_pose2(msg.odom_from_base);
  inbox_.odometry.v = msg.v;
  inbox_.odometry.omega = msg.omega;
  inbox_.odometry.stamp = time::from_utime(msg.utime);
  inbox_.has_odometry = true;
}

bool LldNode::take_stamp(int64_t utime, const std::string& channel)
{
  const std::string why = clock_.observe(utime, channel);
  if (!why.empty()) {
    node_.drops().drop(channel, why);
    return false;
  }
  if (clock_.now() > inbox_.anchor_utime) {
    inbox_.anchor_utime = clock_.now();
    inbox_.anchor_steady = Steady::now();
  }
  return true;
}

time::Time LldNode::message_now() const
{
  int64_t anchor_utime;
  Steady::time_point anchor_steady;
  {
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    anchor_utime = inbox_.anchor_utime;
    anchor_steady = inbox_.anchor_steady;
  }
  const int64_t since = anchor_utime == 0 ? 0
      : std::chrono::duration_cast<std::chrono::microseconds>(Steady::now() - anchor_steady).count();
  return time::from_utime(anchor_utime + since);
}

void LldNode::control_thread()
{
  if (options_.loop.realtime_priority > 0 || options_.loop.lock_memory)
    runtime::request_realtime_logged(fmt::format("control loop at {:.0f} Hz", options_.loop.rate_hz),
                                     options_.loop.realtime_priority, options_.loop.lock_memory,
                                     "no real-time guarantees");
  PeriodicLoop::Tick tick;
  while (loop_.wait(&tick)) {
    const double dt = tick.index == 0 ? 1.0 / options_.loop.rate_hz : tick.dt;
    control_step(message_now(), dt, tick.jitter_ms);
  }
}

void LldNode::control_step(time::Time now, double dt, double jitter_ms)
{
  OdometryInput odometry;
  bool has_odometry;
  std::unique_ptr<Plan> incoming;
  bool has_refresh;
  int64_t refresh_id;
  {
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    odometry = inbox_.odometry;
    has_odometry = inbox_.has_odometry;
    incoming = std::move(inbox_.pending);
    has_refresh = inbox_.has_refresh;
    refresh_id = inbox_.refresh_id;
    inbox_.has_refresh = false;
  }
  if (incoming) {
    // Swap in; the old plan goes back to the inbox for the Node's thread to free.
    // Every arrival empties the slot first (on_trajectory), so it is free here; were it not,
    // `old` would be freed in this thread, the one deallocation the loop could ever make.
    std::unique_ptr<Plan> old = follower_.replace(std::move(incoming), now);
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    if (!inbox_.retired) inbox_.retired = std::move(old);
  }
  if (has_refresh) follower_.refresh(refresh_id, now);
  if (has_odometry) {
    // The loop's own lateness since this odometry came in was the host's (the base driver stalled
    // with it): not held against the odometry's age.
    stall_credit_.on_tick(dt, 1.0 / options_.loop.rate_hz, odometry.stamp);
    odometry.stamp += time::Duration(static_cast<int64_t>(stall_credit_.credit_s() * 1e6));
  }

  // The loop held up longer than the base follows one command (loop.command_deadline_ms): the
  // base's deadman has stopped the robot meanwhile (or will, if it stalled too), so the last
  // command and the reference that ran on describe a past that is gone, and so may the inputs
  // found on waking (the node's thread may already have taken in odometry queued during the
  // gap: it looks fresh). Whether this process alone was stopped (SIGSTOP, then the supervisor's
  // SIGCONT) or the whole host stalled, the first cycle after it commands zero (Follower::halt).
  // Shorter stalls are the stall credit's business: the base kept following meanwhile.
  const double period = 1.0 / options_.loop.rate_hz;
  const bool gap = dt - period > 1e-3 * static_cast<double>(options_.loop.command_deadline_ms);
  const FollowerStatus& before = follower_.status();
  const bool driving = before.state == FollowerState::kTracking || before.state == FollowerState::kStopping ||
                       before.command.v != 0.0 || before.command.omega != 0.0;
  if (gap && driving) {  // logged (a stop); standing still, nothing stops
    loop_gaps_.fetch_add(1, std::memory_order_relaxed);
    last_gap_ms_.store(1e3 * (dt - period), std::memory_order_relaxed);
  }
  const FollowerStatus& st = gap ? follower_.halt(now) : follower_.step(now, dt, has_odometry ? &odometry : nullptr);
  v_command_.store(st.command.v);
  state_.store(static_cast<int>(st.state));
  stop_reason_.store(static_cast<int>(st.stop_reason));
  publish_outputs(now, jitter_ms);
}

void LldNode::publish_outputs(time::Time now, double jitter_ms)
{
  const FollowerStatus& st = follower_.status();
  const bool moving = st.state == FollowerState::kTracking || st.state == FollowerState::kStopping;
  idle_left_ = moving ? options_.loop.idle_commands : std::max(0, idle_left_ - 1);
  if (moving || idle_left_ > 0) {
    cmd_msg_.utime = time::to_utime(now);
    cmd_msg_.seq = ++seq_;
    cmd_msg_.v = st.command.v;
    cmd_msg_.omega = st.command.omega;
    const int n = cmd_msg_.encode(cmd_buf_.data(), 0, static_cast<int>(cmd_buf_.size()));
    if (n > 0) node_.bus().publish(options_.channels.command, cmd_buf_.data(), static_cast<size_t>(n));
  }
  status_msg_.utime = time::to_utime(now);
  status_msg_.trajectory_id = st.trajectory_id;
  status_msg_.state = static_cast<int8_t>(st.state);
  status_msg_.segment_index = st.segment;
  status_msg_.progress = st.progress;
  status_msg_.cross_track_error = st.cross_track;
  status_msg_.heading_error = st.heading_error;
  status_msg_.v_cmd = st.command.v;
  status_msg_.omega_cmd = st.command.omega;
  status_msg_.predicted_end_utime = time::to_utime(st.predicted_end);
  status_msg_.overruns = loop_.overruns();
  status_msg_.period_jitter_ms = static_cast<float>(jitter_ms);
  const int n = status_msg_.encode(status_buf_.data(), 0, static_cast<int>(status_buf_.size()));
  if (n > 0) node_.bus().publish(options_.channels.status, status_buf_.data(), static_cast<size_t>(n));
}

void LldNode::update_heartbeat()
{
  {
    // Free plans the loop handed back.
    std::unique_ptr<Plan> retired;
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    retired = std::move(inbox_.retired);
  }
  const auto state = static_cast<FollowerState>(state_.load());
  const auto reason = static_cast<StopReason>(stop_reason_.load());
  const int64_t overruns = loop_.overruns();
  const int64_t gaps = loop_gaps_.load(std::memory_order_relaxed);
  if (gaps != loop_gaps_logged_) {
    // Worded as the other stops for stale input: a host stall that causes one is counted as such.
    spdlog::warn("controlled stop: stale state, the control loop was held up {:.0f} ms (longer than the base follows a "
                 "command, {} ms; {} times in all): commanded zero, waiting for a trajectory planned after it",
                 last_gap_ms_.load(std::memory_order_relaxed), options_.loop.command_deadline_ms, gaps);
    loop_gaps_logged_ = gaps;
  }
  const bool stale_stop = state == FollowerState::kStopping &&
                          (reason == StopReason::kStaleOdometry || reason == StopReason::kStaleTrajectory);
  // In the log too: a stop for stale input while driving is what a stalled host looks like
  // from here (the fault bench's stress section counts them).
  if (stale_stop && !stale_stop_logged_) spdlog::warn("controlled stop: {}", reason_text(reason));
  stale_stop_logged_ = stale_stop;
  if (stale_stop) {
    node_.set_status(heartbeat_t::STATE_DEGRADED, std::string("controlled stop: ") + reason_text(reason));
  } else if (overruns > 0) {
    node_.set_status(heartbeat_t::STATE_RUNNING, "control loop overruns: " + std::to_string(overruns));
  } else {
    node_.clear_status();
  }
}

}  // namespace rgnav::lld
