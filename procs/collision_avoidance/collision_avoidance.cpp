#include "collision_avoidance/collision_avoidance.h"

#include <cmath>

namespace rgnav::collision_avoidance {

using trajectory::Chain;
using trajectory::Segment;

namespace {
constexpr const char* kTurningAway = "reactive fallback: backing off, turning away";
}  // namespace

const char* mode_name(Mode m)
{
  switch (m) {
    case Mode::kIdle: return "idle";
    case Mode::kPlanned: return "planned";
    case Mode::kReactive: return "reactive fallback";
    case Mode::kBlocked: return "blocked";
    case Mode::kStaleStop: return "stopped: scans stale";
    case Mode::kArrived: return "arrived";
  }
  return "?";
}

CollisionAvoidance::CollisionAvoidance(const CaOptions& options)
    : options_(options), planner_(options.planner), map_(options.map)
{
}

void CollisionAvoidance::set_targets(const Targets& targets)
{
  targets_ = targets;
  has_targets_ = !targets.poses.empty();
  targets_changed_ = true;
  next_ = 0;
}

void CollisionAvoidance::cancel()
{
  targets_ = Targets{};
  has_targets_ = false;
  targets_changed_ = true;
}

void CollisionAvoidance::on_odometry(time::Time, const Pose2& odom_from_base, double v)
{
  pose_ = odom_from_base;
  v_ = v;
  has_pose_ = true;
}

void CollisionAvoidance::on_scan(time::Time stamp, const std::vector<PolarReading>& laser_readings, double range_max)
{
  if (!has_pose_) return;
  ScanPoints sp;
  sp.stamp = stamp;
  sp.odom_from_base = pose_;
  last_readings_.clear();
  sp.laser_origin = options_.base_from_laser.translation();
  const double seen_limit = std::min(range_max, map_.max_range());
  for (const auto& r : laser_readings) {
    const bool hit = r.range < range_max;
    const Eigen::Vector2d base = options_.base_from_laser *
                                 Eigen::Vector2d(r.range * std::cos(r.bearing), r.range * std::sin(r.bearing));
    if (hit) sp.points.push_back(base);
    const double seen = std::min(r.range, seen_limit);
    sp.outline.push_back(options_.base_from_laser * Eigen::Vector2d(seen * std::cos(r.bearing), seen * std::sin(r.bearing)));
    // Polar around the base centre, for the reactive behaviours (no-return beams vote as far).
    last_readings_.push_back({std::atan2(base.y(), base.x()), hit ? base.norm() : std::min(range_max, 8.0)});
  }
  map_.add_scan(std::move(sp));
  last_scan_ = stamp;
  has_scan_ = true;
}

void CollisionAvoidance::on_obstacle_points(time::Time stamp, std::vector<Eigen::Vector2d> odom_points)
{
  map_.set_grid_points(stamp, std::move(odom_points));
}

std::vector<Pose2> CollisionAvoidance::goals() const
{
  std::vector<Pose2> out;
  const auto& p = targets_.poses;
  for (size_t i = next_; i < p.size() && static_cast<int>(out.size()) < options_.lookahead_targets; ++i) {
    const bool last = i + 1 == p.size();
    double heading = p[i].theta();
    if (!last || !targets_.final_is_goal) {
      // Intermediate targets: arrive heading toward the one after (smooth passage).
      const Eigen::Vector2d d = (last ? p[i].translation() - (i > 0 ? p[i - 1].translation() : pose_.translation())
                                      : p[i + 1].translation() - p[i].translation());
      if (d.norm() > 1e-6) heading = std::atan2(d.y(), d.x());
    }
    out.emplace_back(p[i].translation(), heading);
  }
  return out;
}

bool CollisionAvoidance::advance_targets()
{
  bool advanced = false;
  while (next_ < targets_.poses.size()) {
    const bool final = next_ + 1 == targets_.poses.size();
    const double dist = (targets_.poses[next_].translation() - pose_.translation()).norm();
    if (final && targets_.final_is_goal) break;  // the goal is reached by arriving, below
    if (dist > options_.reach_radius) break;
    ++next_;
    advanced = true;
  }
  return advanced;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::send_new(Chain chain, time::Time now, double predicted,
                                                                   Mode mode)
{
  trajectory::Trajectory t;
  t.id = next_id_++;
  t.stamp = now;
  t.chain = std::move(chain);
  t.a_max = options_.a_max;
  t.omega_max = options_.omega_max;
  t.stop_at_end = true;
  t.predicted_end = now + time::Duration(static_cast<int64_t>(predicted * 1e6));
  active_ = t;
  last_sent_ = now;
  stopped_ = t.chain.empty();
  mode_ = mode;
  return t;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::stop(time::Time now, Mode mode, const std::string& why)
{
  status_ = why;
  if (stopped_ && mode_ == mode) {
    // Keep the stop fresh only as often as a refresh.
    if (time::to_seconds(now - last_sent_) < options_.refresh_period) return std::nullopt;
    last_sent_ = now;
    return active_;
  }
  return send_new(Chain(), now, 0.0, mode);
}

std::optional<trajectory::Trajectory> CollisionAvoidance::update(time::Time now)
{
  if (!has_pose_) return std::nullopt;
  if (has_targets_ && (!has_scan_ || time::to_seconds(now - last_scan_) > options_.scan_timeout))
    return stop(now, Mode::kStaleStop, "stopped: no fresh scan");
  if (updated_once_ && time::to_seconds(now - last_update_) < options_.update_period && !targets_changed_)
    return std::nullopt;
  updated_once_ = true;
  last_update_ = now;
  map_.rebuild(now);
  if (!has_progress_pose_ || (pose_.translation() - progress_pose_).norm() > options_.headway) {
    has_progress_pose_ = true;
    progress_pose_ = pose_.translation();
    progress_since_ = now;
  }

  if (!has_targets_) {
    has_progress_pose_ = false;  // idle is no lack of headway: the clock starts with the next targets
    const bool was_moving = active_ && !stopped_;
    if (targets_changed_ || was_moving) {
      targets_changed_ = false;
      return stop(now, Mode::kIdle, "idle");
    }
    mode_ = Mode::kIdle;
    status_ = "idle";
    return std::nullopt;
  }

  // A back-off manoeuvre runs to its end: re-deciding every 100 ms on a clearance that
  // flickers around the threshold (scan noise) made the robot twitch between turning away
  // and turning back.
  if (backoff_id_ && active_ && active_->id == *backoff_id_ && !targets_changed_) {
    const bool ours = has_feedback_ && feedback_.trajectory_id == *backoff_id_;
    const bool ended = ours && (feedback_.state == 2 || feedback_.state == 0);
    // Committed, but never blind: something on what remains of it ends it.
    const bool blocked = first_collision(active_->chain, map_, options_.planner.robot_radius + options_.planner.safety_margin,
                                         options_.planner.check_step, ours ? feedback_.progress : 0.0)
                             .has_value();
    if (!ended && !blocked && now < backoff_until_) {
      if (time::to_seconds(now - last_sent_) >= options_.refresh_period) {
        last_sent_ = now;
        return active_;  // keep-alive
      }
      return std::nullopt;
    }
  }
  backoff_id_.reset();

  bool replan = targets_changed_ || !active_ || stopped_ || mode_ == Mode::kReactive || mode_ == Mode::kBlocked;
  targets_changed_ = false;
  if (advance_targets()) replan = true;
  const bool final_goal = targets_.final_is_goal;
  const Pose2& goal = targets_.poses.back();
  if (final_goal && next_ + 1 == targets_.poses.size() &&
      (goal.translation() - pose_.translation()).norm() < options_.goal_tolerance + 0.02 &&
      (!has_feedback_ || feedback_.state != 1 || feedback_.trajectory_id != (active_ ? active_->id : 0))) {
    mode_ = Mode::kArrived;
    status_ = "arrived";
    has_targets_ = false;
    return std::nullopt;
  }
  if (!final_goal && next_ >= targets_.poses.size()) {
    mode_ = Mode::kArrived;
    status_ = "targets passed";
    has_targets_ = false;
    return std::nullopt;
  }

  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  if (!replan && active_) {
    const bool ours = has_feedback_ && feedback_.trajectory_id == active_->id;
    const double progress = ours ? feedback_.progress : 0.0;
    // An obstacle on what remains of the chain (look a little behind the progress, too).
    if (first_collision_near(active_->chain, map_, options_.planner, std::max(0.0, progress - 0.1))) replan = true;
    if (ours && (feedback_.state == 2 || feedback_.state == 0)) replan = true;  // ended short of the target
    if (ours && std::fabs(feedback_.cross_track) > options_.replan_cross_track) replan = true;
  }
  if (!replan) {
    if (time::to_seconds(now - last_sent_) >= options_.refresh_period) {
      last_sent_ = now;
      return active_;  // keep-alive: same id, the drive keeps following
    }
    return std::nullopt;
  }

  const double v_now = has_feedback_ ? feedback_.v_cmd : v_;
  // An intermediate target an obstacle now sits on (or beside) cannot be reached: aim past it.
  while (next_ + 1 < targets_.poses.size() &&
         map_.clearance(targets_.poses[next_].translation(), clearance) < clearance)
    ++next_;
  auto planned = planner_.plan(pose_, v_now, goals(), map_, targets_.max_speed);
  if (!planned && next_ + 1 < targets_.poses.size()) {
    // The next target cannot be reached from here; the one after may be.
    const size_t keep = next_;
    ++next_;
    planned = planner_.plan(pose_, v_now, goals(), map_, targets_.max_speed);
    if (!planned) next_ = keep;
  }
  bool detour = false;
  if (!planned) {
    // No candidate of the chain planner is free: look for a way around on the grid.
    const auto g = goals();
    if (!g.empty()) {
      const bool is_goal = final_goal && next_ + 1 == targets_.poses.size();
      if (auto corners = grid_path(map_, pose_.translation(), g.front().translation(), clearance, options_.grid)) {
        planned = planner_.plan_along(pose_, v_now, *corners, is_goal ? std::optional<double>(g.front().theta()) : std::nullopt,
                                      map_, std::min(targets_.max_speed, options_.detour_speed));
        detour = planned.has_value();
      }
    }
  }
  if (planned) {
    blocked_since_set_ = false;
    ++replans_;
    if (detour) ++detours_;
    status_ = detour ? "planned: detour" : "planned";
    return send_new(std::move(planned->chain), now, planned->predicted_time, Mode::kPlanned);
  }
  return reactive(now);
}

std::optional<trajectory::Trajectory> CollisionAvoidance::backing_off(time::Time now, double radius)
{
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const Eigen::Vector2d here = pose_.translation();
  if (map_.clearance(here, radius) >= radius) return std::nullopt;
  Eigen::Vector2d away = Eigen::Vector2d::Zero();
  for (const auto& p : map_.points()) {
    const Eigen::Vector2d d = here - p;
    const double n = d.norm();
    if (n < radius + 0.1 && n > 1e-6) away += d / n;
  }
  if (away.norm() < 1e-6) return std::nullopt;  // surrounded evenly: nothing better than waiting
  const double heading = std::atan2(away.y(), away.x());
  const double dth = geometry::normalize_angle(heading - pose_.theta());
  const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
  const bool turn_first = std::fabs(dth) > 0.3;
  if (turn_first && !standing) return stop(now, Mode::kReactive, "reactive fallback: backing off, stopping first");
  // Turn and drive out as one committed manoeuvre: turning first and deciding the way out
  // afterwards made the robot turn back and forth beside a person who stood waiting for it
  // (what the laser saw of them changed with every turn, and so did "away").
  Segment out = Segment::line(Pose2(here, heading), options_.backoff_length);
  out.set_v_max(options_.backoff_speed);
  Chain c = turn_first ? Chain({Segment::turn(pose_, dth), out}) : Chain({out});
  const double t_turn = turn_first ? trajectory::turn_duration(dth, options_.omega_max, 1.0) : 0.0;
  if (first_collision(c, map_, clearance, options_.planner.check_step)) {
    if (!turn_first) return std::nullopt;
    // No way out that way: still face it (the turn brings the space there into view).
    if (active_ && !stopped_ && mode_ == Mode::kReactive && status_ == kTurningAway &&
        time::to_seconds(now - last_sent_) < t_turn)
      return std::nullopt;  // the turn is under way
    status_ = kTurningAway;
    return commit_backoff(send_new(Chain({Segment::turn(pose_, dth)}), now, t_turn, Mode::kReactive), now, t_turn);
  }
  status_ = turn_first ? "reactive fallback: backing off, turning and driving away" : "reactive fallback: backing off, driving away";
  const double t = t_turn + options_.backoff_length / options_.backoff_speed;
  return commit_backoff(send_new(std::move(c), now, t, Mode::kReactive), now, t);
}

std::optional<trajectory::Trajectory> CollisionAvoidance::commit_backoff(std::optional<trajectory::Trajectory> t,
                                                                         time::Time now, double duration)
{
  if (t) {
    backoff_id_ = t->id;
    // Its predicted duration plus the acceleration phases and some slack; then decide anew.
    backoff_until_ = now + time::Duration(static_cast<int64_t>((duration + 2.0) * 1e6));
  }
  return t;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::reactive(time::Time now)
{
  ++fallbacks_;
  const Pose2 target = goals().empty() ? pose_ : goals().front();
  const Eigen::Vector2d d = pose_.inverse() * target.translation();
  const double bearing = std::atan2(d.y(), d.x());
  const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
  if (!blocked_since_set_) {
    blocked_since_set_ = true;
    blocked_since_ = now;
  }
  // No headway for a long time: whoever waits with the robot (a person at their personal
  // space, who will not walk on while the robot stands in their way) gets room. Back away
  // from what is near, farther out than the plain back-off looks.
  if (time::to_seconds(now - progress_since_) > options_.yield_after) {
    progress_since_ = now;
    const double reach = options_.planner.robot_radius + options_.planner.safety_margin + options_.yield_reach;
    if (auto away = backing_off(now, reach)) {
      status_ = "reactive fallback: no headway, yielding";
      return away;
    }
  }
  // First behaviour: stop and wait a moment (a person crossing clears the way by itself),
  // but not where a person is about to walk: they would walk into the robot.
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const bool in_the_way = map_.clearance_predicted(pose_.translation(), clearance) < clearance;
  if (!in_the_way && time::to_seconds(now - blocked_since_) < options_.fallback_wait)
    return stop(now, Mode::kReactive, "reactive fallback: stopped, waiting for the way to clear");
  // Too close to something (a person who stepped up to the robot and now waits for it to
  // move, a box seen late): nothing that keeps the full clearance starts here. Back off:
  // face away from what is close (a turn on the spot is always safe for the round B21r,
  // and brings the space there into the laser's view), then drive out along that heading.
  if (auto away = backing_off(now, clearance)) return away;
  // Readings: the newest scan plus the map's other obstacles (3D grid, older scans) near by.
  std::vector<PolarReading> readings = last_readings_;
  const Pose2 base_from_odom = pose_.inverse();
  for (const auto& p : map_.points()) {
    const Eigen::Vector2d b = base_from_odom * p;
    if (b.norm() < 3.0) readings.push_back({std::atan2(b.y(), b.x()), b.norm()});
  }
  const ReactiveDecision dec = decide(readings, bearing, standing, options_.reactive);
  if (dec.action == ReactiveDecision::Action::kTurn) {
    Chain c({Segment::turn(pose_, dec.heading)});
    status_ = "reactive fallback: turning toward free space";
    const double t = trajectory::turn_duration(dec.heading, options_.omega_max, 1.0);
    if (active_ && !stopped_ && mode_ == Mode::kReactive && time::to_seconds(now - last_sent_) < t) return std::nullopt;
    return send_new(std::move(c), now, t, Mode::kReactive);
  }
  // Free space leads away from the target (back down the corridor the robot came along):
  // driving there only loses ground. Face the target's side and plan again from there.
  if (dec.action == ReactiveDecision::Action::kDrive &&
      std::fabs(geometry::normalize_angle(dec.heading - bearing)) > M_PI_2) {
    if (!standing) return stop(now, Mode::kReactive, "reactive fallback: free space leads away, stopping");
    const double turn = std::clamp(bearing, -options_.reactive.max_turn, options_.reactive.max_turn);
    const double t = trajectory::turn_duration(turn, options_.omega_max, 1.0);
    if (active_ && !stopped_ && mode_ == Mode::kReactive && time::to_seconds(now - last_sent_) < t) return std::nullopt;
    status_ = "reactive fallback: turning toward the target";
    blocked_since_ = now;
    return send_new(Chain({Segment::turn(pose_, turn)}), now, t, Mode::kReactive);
  }
  if (dec.action == ReactiveDecision::Action::kDrive) {
    const double L = options_.reactive.step_length;
    Segment arc = Segment::arc(pose_, std::clamp(dec.heading / L, -options_.planner.kappa_max, options_.planner.kappa_max), L);
    arc.set_v_max(std::max(0.05, dec.speed));
    Chain c({arc});
    if (!first_collision(c, map_, options_.planner.robot_radius + 0.5 * options_.planner.safety_margin,
                         options_.planner.check_step)) {
      status_ = "reactive fallback: steering toward free space";
      return send_new(std::move(c), now, L / std::max(0.05, dec.speed), Mode::kReactive);
    }
  }
  blocked_since_ = now;  // nothing to do but stand: wait again before the next try
  return stop(now, Mode::kReactive, "reactive fallback: stopped, obstacle ahead");
}

}  // namespace rgnav::collision_avoidance
