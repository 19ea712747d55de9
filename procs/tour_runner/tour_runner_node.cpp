#include "procs/tour_runner/tour_runner_node.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "msg/conversions.h"
#include "rgnav/target_list_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"

namespace rgnav::tour_runner {

TourRunnerOptions load_options(const config::Config& t, const config::Config& f, const config::RobotDescription& robot,
                               const std::string& config_dir)
{
  TourRunnerOptions o;
  o.tour_file = t.required_string("file");
  if (!o.tour_file.empty() && o.tour_file[0] != '/') o.tour_file = config_dir + "/" + o.tour_file;
  o.max_spacing = t.number("max_spacing_m", o.max_spacing, 0.5, 2.0);
  o.sequencer.reach_radius = t.number("reach_radius_m", o.sequencer.reach_radius, 0.05, 2.0);
  o.sequencer.lookahead = static_cast<int>(t.integer("lookahead", o.sequencer.lookahead, 1, 20));
  o.output = t.choice("output", "base_cmd", {"base_cmd", "targets"}) == "targets" ? TourRunnerOptions::Output::kTargets
                                                                               : TourRunnerOptions::Output::kBaseCmd;
  o.exit_when_done = t.boolean("exit_when_done", o.exit_when_done);
  o.max_speed = t.number("max_speed_mps", o.max_speed, 0.05, 2.0);
  o.scan_stale_s = t.number("scan_stale_s", o.scan_stale_s, 0.05, 5.0);
  o.cmd_deadline_us = static_cast<int32_t>(t.integer("cmd_deadline_us", o.cmd_deadline_us, 10'000, 1'000'000));
  o.base_from_laser = robot.laser_front.base_from_laser;
  o.follower.max_v = f.number("max_v_mps", o.follower.max_v, 0.05, 1.5);
  o.follower.max_omega = f.number("max_omega_radps", o.follower.max_omega, 0.1, 3.0);
  o.follower.turn_in_place_angle = f.number("turn_in_place_rad", o.follower.turn_in_place_angle, 0.1, M_PI);
  o.follower.robot_radius = robot.radius;
  o.follower.stop_distance = f.number("stop_distance_m", o.follower.stop_distance, 0.0, 2.0);
  o.follower.slow_distance = f.number("slow_distance_m", o.follower.slow_distance, 0.05, 5.0);
  if (o.follower.slow_distance <= o.follower.stop_distance) f.fail("slow_distance_m", "must exceed stop_distance_m");
  return o;
}

Channels load_channels(const config::Config& c)
{
  Channels ch;
  ch.odometry = c.string("odometry", ch.odometry);
  ch.laser = c.string("laser", ch.laser);
  ch.slam_pose = c.string("slam_pose", ch.slam_pose);
  ch.targets = c.string("targets", ch.targets);
  ch.base_cmd = c.string("base_cmd", ch.base_cmd);
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
