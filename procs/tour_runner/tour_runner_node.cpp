#include "procs/tour_runner/tour_runner_node.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "config/string_fields.h"
#include "msg/conversions.h"
#include "rgnav/target_list_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"

namespace rgnav::tour_runner {

Channels load_channels(const config::Config& c)
{
  Channels ch;
  config::read_strings(c, {{"odometry", &ch.odometry}, {"laser", &ch.laser}, {"slam_pose", &ch.slam_pose},
                           {"targets", &ch.targets}, {"base_cmd", &ch.base_cmd}});
  return ch;
}

TourRunnerNode::TourRunnerNode(runtime::Node& node, const TourRunnerOptions& options, const Channels& channels)
    : node_(node), options_(options), channels_(channels)
{
  const Tour tour = load_tour(options_.tour_file);
  // Odometry starts at identity where the robot stands, so the odom (and map) frame is the
  // start pose.
  map_from_world_ = tour.world_from_start.inverse();
  world_targets_ = densify(tour.world_points, tour.world_from_start.translation(), options_.max_spacing);
  spdlog::info("tour {}: {} waypoints, {} targets", options_.tour_file, tour.world_points.size(), world_targets_.size());
  node_.subscribe<odometry_t>(channels_.odometry, [this](const odometry_t& m) { on_odometry(m); });
  if (options_.output == TourRunnerOptions::Output::kBaseCmd)
    node_.subscribe<laser_scan_t>(channels_.laser, [this](const laser_scan_t& m) { on_scan(m); });
  if (!channels_.slam_pose.empty())
    node_.subscribe<slam_pose_t>(channels_.slam_pose, [this](const slam_pose_t& m) { on_slam_pose(m); });
}

void TourRunnerNode::on_slam_pose(const slam_pose_t& m)
{
  const geometry::Pose2 odom_from_map = msg::to_pose2(m.map_from_odom).inverse();
  const double jump = (odom_from_map.translation() - odom_from_map_.translation()).norm();
  if (jump > 0.5) spdlog::info("SLAM correction moved the targets by {:.2f} m (loop closure)", jump);
  odom_from_map_ = odom_from_map;
}

void TourRunnerNode::on_scan(const laser_scan_t& m)
{
  obstacles_.clear();
  for (int i = 0; i < m.nranges; ++i) {
    const double r = m.ranges[static_cast<size_t>(i)];
    if (r <= m.range_min || r >= m.range_max) continue;
    const double a = m.angle_min + i * m.angle_increment;
    obstacles_.push_back(options_.base_from_laser * Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
  }
  last_scan_utime_ = m.utime;
}

void TourRunnerNode::on_odometry(const odometry_t& m)
{
  if (finished_) return;
  const geometry::Pose2 odom_from_base = msg::to_pose2(m.odom_from_base);
  if (!sequencer_) {
    std::vector<Eigen::Vector2d> map_targets;
    for (const auto& w : world_targets_) map_targets.push_back(map_from_world_ * w);
    sequencer_.emplace(options_.sequencer, std::move(map_targets));
  }
  const bool advanced = sequencer_->update(odom_from_map_.inverse() * odom_from_base);
  if (advanced) spdlog::info("target {}/{} reached", sequencer_->reached(), sequencer_->size());

  if (sequencer_->done()) {
    finished_ = true;
    spdlog::info("tour complete: {} targets reached", sequencer_->size());
    if (options_.output == TourRunnerOptions::Output::kBaseCmd) publish_cmd(m.utime, 0, 0);
    else publish_targets(m.utime);
    node_.set_status(heartbeat_t::STATE_RUNNING, "tour complete");
    if (options_.exit_when_done) node_.request_stop();
    return;
  }

  if (options_.output == TourRunnerOptions::Output::kTargets) {
    if (advanced || m.seq % 25 == 0) publish_targets(m.utime);  // on change, and ~2 Hz at 50 Hz odometry
    return;
  }
  // Simple follower. Fail safe: no recent scan, no motion.
  const bool scan_fresh = last_scan_utime_ > 0 && (m.utime - last_scan_utime_) < options_.scan_stale_s * 1e6;
  if (!scan_fresh) {
    if (!blocked_) spdlog::warn("no recent scan: holding still");
    blocked_ = true;
    node_.set_status(heartbeat_t::STATE_DEGRADED, "no recent scan: holding still");
    publish_cmd(m.utime, 0, 0);
    return;
  }
  if (escape_) {
    // Leave the blocked spot along the committed free heading: 0.5 m, or 3 s at most.
    const bool done = (odom_from_base.translation() - escape_->odom_start.translation()).norm() >= 0.5 ||
                      m.utime - escape_->start_utime > 3'000'000;
    if (!done) {
      const double err = geometry::normalize_angle(escape_->odom_heading - odom_from_base.theta());
      const Command e = escape(options_.follower, err, obstacles_);
      publish_cmd(m.utime, e.v, e.omega);
      return;
    }
    escape_.reset();
  }
  const Command c = pursue(options_.follower, odom_from_base, odom_from_map_ * sequencer_->upcoming().front(), obstacles_);
  if (c.blocked && std::isfinite(c.escape_heading))
    escape_ = Escape{odom_from_base, odom_from_base.theta() + c.escape_heading, m.utime};
  if (c.blocked != blocked_) {
    blocked_ = c.blocked;
    if (blocked_) spdlog::warn("path to target {}/{} blocked: waiting", sequencer_->reached() + 1, sequencer_->size());
    else spdlog::info("path clear again");
  }
  if (c.blocked) node_.set_status(heartbeat_t::STATE_DEGRADED, "path blocked: waiting");
  else node_.clear_status();
  publish_cmd(m.utime, c.v, c.omega);
}

void TourRunnerNode::publish_targets(int64_t utime)
{
  target_list_t t;
  t.utime = utime;
  t.goal_id = sequencer_->goal_id();
  for (const auto& p : sequencer_->upcoming())
    t.odom_from_target.push_back(msg::to_msg(geometry::Pose2(odom_from_map_ * p, 0.0)));
  t.ntargets = static_cast<int32_t>(t.odom_from_target.size());
  t.max_speed = static_cast<float>(options_.max_speed);
  t.final_is_goal = sequencer_->reached() + t.odom_from_target.size() >= sequencer_->size();
  node_.publish(channels_.targets, t);
}

void TourRunnerNode::publish_cmd(int64_t utime, double v, double omega)
{
  velocity_cmd_t c;
  c.utime = utime;
  c.seq = ++cmd_seq_;
  c.v = v;
  c.omega = omega;
  c.deadline_us = options_.cmd_deadline_us;
  c.source = node_.name();
  node_.publish(channels_.base_cmd, c);
}

}  // namespace rgnav::tour_runner
