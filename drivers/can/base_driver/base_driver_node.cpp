#include "base_driver/base_driver_node.h"

#include <spdlog/spdlog.h>

#include "rgnav/heartbeat_t.hpp"
#include "time/message_time.h"

namespace rgnav::can::base {

BaseDriverNodeOptions load_base_driver_node_options(const config::Config& root)
{
  BaseDriverNodeOptions o;
  const auto ch = root.section("channels");
  o.base_cmd_channel = ch.string("base_cmd", o.base_cmd_channel);
  o.odometry_channel = ch.string("odometry", o.odometry_channel);
  o.odometry_rate_hz = root.section("base").number("odometry_rate_hz", o.odometry_rate_hz, 1.0, 200.0);
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
    : node_(node), options_(options), driver_(std::move(driver))
{
  node_.subscribe<velocity_cmd_t>(options_.base_cmd_channel, [this](const velocity_cmd_t& msg) {
    driver_->command(to_velocity_command(msg), command_deadline(msg));
  });
  node_.every(std::chrono::microseconds(static_cast<int64_t>(1e6 / options_.odometry_rate_hz)),
              [this] { publish_odometry(); });
  node_.set_status(heartbeat_t::STATE_STARTING, "bringing drives up");
  driver_->start();
}

BaseDriverNode::~BaseDriverNode() { driver_->stop(); }

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
  // The state is always the drives' (not the runtime's input-based guess): a base driver
  // without commands is running, holding the robot still.
  if (o.status == BaseStatus::kFault)
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
