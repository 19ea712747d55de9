#include "collision_avoidance/ca_node.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <climits>

#include "collision_avoidance/grid_obstacles.h"
#include "msg/conversions.h"
#include "rgnav/ca_status_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/lld_status_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "rgnav/obstacle_grid_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/target_list_t.hpp"
#include "trajectory/trajectory_conversions.h"

namespace rgnav::collision_avoidance {

CaNode::CaNode(runtime::Node& node, const CaNodeOptions& options)
    : node_(node), options_(options), ca_(options.ca)
{
  const auto& ch = options_.channels;
  node_.subscribe<target_list_t>(ch.targets, [this](const target_list_t& m) {
    Targets t;
    t.goal_id = m.goal_id;
    t.max_speed = m.max_speed;
    t.final_is_goal = m.final_is_goal;
    for (const auto& p : m.odom_from_target) t.poses.push_back(msg::to_pose2(p));
    goal_id_ = m.goal_id;
    ca_.set_targets(t);
    decide(node_.clock().now());
  });
  node_.subscribe<nav_goal_t>(ch.nav_goal, [this](const nav_goal_t& m) {
    if (!m.cancel) return;  // goals reach collision avoidance as TARGETS from the planner
    ca_.cancel();
    goal_id_ = 0;
    decide(node_.clock().now());
  });
  node_.subscribe<odometry_t>(ch.odometry, [this](const odometry_t& m) {
    const auto t = time::from_utime(m.utime);
    ca_.on_odometry(t, msg::to_pose2(m.odom_from_base), m.v);
    decide(t);
  });
  node_.subscribe<laser_scan_t>(ch.laser, [this](const laser_scan_t& m) {
    std::vector<PolarReading> r;
    r.reserve(m.ranges.size());
    for (size_t i = 0; i < m.ranges.size(); ++i) {
      const float d = m.ranges[i];
      if (d <= 0.f || d < m.range_min) continue;  // invalid reading
      r.push_back({m.angle_min + static_cast<double>(i) * m.angle_increment, static_cast<double>(d)});
    }
    const auto t = time::from_utime(m.utime);
    ca_.on_scan(t, r, m.range_max);
    decide(t);
  });
  node_.subscribe<obstacle_grid_t>(ch.obstacles, [this](const obstacle_grid_t& m) {
    ca_.on_obstacle_points(time::from_utime(m.utime),
                           grid_obstacle_points(msg::to_pose2(m.odom_from_grid), m.resolution, m.width, m.height, m.cells,
                                                options_.ca.map.grid_occupied_min));
  });
  node_.subscribe<lld_status_t>(ch.lld_status, [this](const lld_status_t& m) {
    DriveFeedback f;
    f.trajectory_id = m.trajectory_id;
    f.state = m.state;
    f.progress = m.progress;
    f.cross_track = m.cross_track_error;
    f.v_cmd = m.v_cmd;
    ca_.on_drive_feedback(f);
  });
}

void CaNode::decide(time::Time now)
{
  const auto t = ca_.update(now);
  if (t) node_.publish(options_.channels.trajectory, trajectory::to_msg(*t, nullptr, options_.ca.planner.limits.v_max));
  if (ca_.mode() != reported_ || ca_.status() != reported_text_) {
    reported_ = ca_.mode();
    reported_text_ = ca_.status();
    const bool degraded = reported_ == Mode::kReactive || reported_ == Mode::kStaleStop || reported_ == Mode::kBlocked;
    if (degraded) {
      node_.set_status(heartbeat_t::STATE_DEGRADED, reported_text_);
      spdlog::warn("{}", reported_text_);
    } else {
      node_.set_status(heartbeat_t::STATE_RUNNING, reported_text_);
    }
  }
  publish_status(now);
}

namespace {

int8_t to_msg_mode(Mode m)
{
  switch (m) {
    case Mode::kIdle: return ca_status_t::MODE_IDLE;
    case Mode::kPlanned: return ca_status_t::MODE_PLANNED;
    case Mode::kReactive: return ca_status_t::MODE_REACTIVE;
    case Mode::kBlocked: return ca_status_t::MODE_BLOCKED;
    case Mode::kStaleStop: return ca_status_t::MODE_STALE_STOP;
    case Mode::kArrived: return ca_status_t::MODE_ARRIVED;
    case Mode::kYielding: return ca_status_t::MODE_YIELDING;
  }
  return ca_status_t::MODE_IDLE;
}

}  // namespace

void CaNode::publish_status(time::Time now)
{
  const Mode mode = ca_.mode();
  // Stuck: no chain to the targets (reactive fallbacks, or standing blocked). The span runs
  // until a chain is planned again, whatever the fallbacks do meanwhile (backing off, turning
  // and yielding move the robot, but not toward its targets).
  const bool stuck = mode == Mode::kReactive || mode == Mode::kBlocked;
  if (!stuck) stuck_since_.reset();
  else if (!stuck_since_) stuck_since_ = now;
  if (options_.channels.status.empty()) return;
  constexpr time::Duration kPeriod = std::chrono::milliseconds(500);
  if (status_sent_ && mode == status_mode_ && now < status_sent_at_ + kPeriod && now >= status_sent_at_) return;
  ca_status_t m;
  m.utime = time::to_utime(now);
  m.goal_id = goal_id_;
  m.mode = to_msg_mode(mode);
  m.blocked_s = stuck_since_ ? std::max(0.0, time::to_seconds(now - *stuck_since_)) : 0.0;
  m.next_target = static_cast<int32_t>(std::min<size_t>(ca_.next_target(), INT32_MAX));
  m.status = ca_.status().substr(0, 256);
  node_.publish(options_.channels.status, m);
  status_sent_ = true;
  status_mode_ = mode;
  status_sent_at_ = now;
}

}  // namespace rgnav::collision_avoidance
