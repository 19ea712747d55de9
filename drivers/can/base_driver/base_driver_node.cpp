#include "base_driver/base_driver_node.h"

#include <spdlog/spdlog.h>

#include "config/duration_fields.h"
#include "rgnav/heartbeat_t.hpp"
#include "time/message_time.h"

namespace rgnav::can::base {

BaseDriverNodeOptions load_base_driver_node_options(const config::Config& root)
{
  BaseDriverNodeOptions o;
  const auto ch = root.section("channels");
  o.base_cmd_channel = ch.string("base_cmd", o.base_cmd_channel);
  o.odometry_channel = ch.string("odometry", o.odometry_channel);
  const auto base = root.section("base");
  o.odometry_rate_hz = base.number("odometry_rate_hz", o.odometry_rate_hz, 1.0, 200.0);
  o.sources.owner = base.string("command_source", o.sources.owner);
  o.sources.hold_source = base.string("hold_source", o.sources.hold_source);
  o.sources.foreign_quiet = config::milliseconds(base, "foreign_quiet_ms", o.sources.foreign_quiet, 100, 60000);
  if (o.sources.owner.empty()) base.fail("command_source", "must name the process that drives (lld's node name)");
  if (o.sources.hold_source == o.sources.owner) base.fail("hold_source", "must differ from command_source");
  return o;
}

VelocityCommand to_velocity_command(const velocity_cmd_t& msg) { return {msg.v, msg.omega}; }

std::chrono::microseconds command_deadline(const velocity_cmd_t& msg) { return std::chrono::microseconds(msg.deadline_us); }

odometry_t to_odometry_msg(const BaseOdometry& o, int64_t utime, int64_t seq)
{
  odometry_t m;
  m.utime = utime;
  m.seq = seq;
  m.odom_from_base.x = o.pose.x;
  m.odom_from_base.y = o.pose.y;
  m.odom_from_base.theta = o.pose.theta;
  m.v = o.v;
  m.omega = o.omega;
  m.distance = o.distance;
  switch (o.status) {
    case BaseStatus::kOk: m.status = odometry_t::STATUS_OK; break;
    case BaseStatus::kStopped: m.status = odometry_t::STATUS_STOPPED; break;
    case BaseStatus::kFault: m.status = odometry_t::STATUS_FAULT; break;
  }
  return m;
}

BaseDriverNode::BaseDriverNode(runtime::Node& node, const BaseDriverNodeOptions& options,
                               std::unique_ptr<BaseDriver> driver)
    : node_(node), options_(options), driver_(std::move(driver)), gate_(options_.sources)
{
  node_.subscribe<velocity_cmd_t>(options_.base_cmd_channel, [this](const velocity_cmd_t& msg) { on_command(msg); });
  node_.every(std::chrono::microseconds(static_cast<int64_t>(1e6 / options_.odometry_rate_hz)),
              [this] { publish_odometry(); });
  node_.set_status(heartbeat_t::STATE_STARTING, "bringing drives up");
  driver_->start();
}

BaseDriverNode::~BaseDriverNode() { driver_->stop(); }

void BaseDriverNode::on_command(const velocity_cmd_t& msg)
{
  const auto now = std::chrono::steady_clock::now();
  const CommandDecision d = gate_.on_command(msg.source, msg.v, msg.omega, command_deadline(msg), now);
  // A second source is a safety event: the drives quick-stop from this very message on, and stay
  // held while it speaks (released by publish_odometry() or the owner's next command once it
  // has been silent for foreign_quiet).
  if (gate_.locked_out(now))
    driver_->quick_stop(true, "second source on BASE_CMD ('" + gate_.foreign_source() + "')");
  else
    driver_->quick_stop(false);
  if (d.verdict == CommandVerdict::kFollow) {
    driver_->command(to_velocity_command(msg), command_deadline(msg));
    return;
  }
  // The hold (or the quick stop's target): zero; the hold is a controlled stop on the drives'
  // profile ramps, as for a stale command.
  driver_->command(VelocityCommand{}, command_deadline(msg));
  if (!d.alert.empty()) {
    spdlog::error("ALERT: {}", d.alert);
    node_.set_status(heartbeat_t::STATE_DEGRADED, d.alert);
  }
}

void BaseDriverNode::publish_odometry()
{
  const BaseSnapshot s = driver_->snapshot();
  // utime: when the encoders were sampled; before the first sample, now. Never backwards.
  int64_t utime = s.sample_wall_utime > 0 ? s.sample_wall_utime : time::wall_utime();
  if (utime < last_utime_) utime = last_utime_;
  last_utime_ = utime;
  node_.publish(options_.odometry_channel, to_odometry_msg(s.odometry, utime, ++seq_));

  const BaseOdometry& o = s.odometry;
  if (o.status != last_status_ || (o.status == BaseStatus::kFault && o.reason != last_reason_)) {
    if (o.status == BaseStatus::kFault)
      spdlog::error("base stopped by a fault: {}", o.reason);
    else if (last_status_ == BaseStatus::kFault)
      spdlog::info("base recovered ({})", to_string(o.status));
  }
  // A second source on BASE_CMD holds the drives at zero until it is silent: that alert first.
  const bool locked_out = gate_.locked_out(std::chrono::steady_clock::now());
  if (!locked_out) driver_->quick_stop(false);
  if (locked_out_ && !locked_out)
    spdlog::warn("BASE_CMD: '{}' silent for {} ms: following '{}' again ({} commands refused in all)", gate_.foreign_source(),
                 options_.sources.foreign_quiet.count(), options_.sources.owner, gate_.refused());
  locked_out_ = locked_out;
  // The state is always the drives' (not the runtime's input-based guess): a base driver
  // without commands is running, holding the robot still.
  if (locked_out)
    node_.set_status(heartbeat_t::STATE_DEGRADED, gate_.alert());
  else if (o.status == BaseStatus::kFault)
    node_.set_status(heartbeat_t::STATE_DEGRADED, "drive fault: " + o.reason);
  else if (o.status == BaseStatus::kStopped && o.reason.rfind("bringing", 0) == 0)
    node_.set_status(heartbeat_t::STATE_STARTING, o.reason);
  else if (o.status == BaseStatus::kStopped)
    node_.set_status(heartbeat_t::STATE_RUNNING, "stopped: " + o.reason);
  else
    node_.set_status(heartbeat_t::STATE_RUNNING, "ok");
  last_status_ = o.status;
  last_reason_ = o.reason;
}

}  // namespace rgnav::can::base
