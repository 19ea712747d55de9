#include "collision_avoidance/collision_avoidance.h"

#include <algorithm>
#include <cmath>

#include "geometry/pose_track.h"

namespace rgnav::collision_avoidance {

using trajectory::Chain;
using trajectory::Segment;

namespace {

constexpr double kOdometryKept = 1.0;     // [s]
constexpr int64_t kOdometryGapUs = 100'000; // odometry messages further apart bracket no scan

PlannerOptions squeeze_options(const CaOptions& o)
{
  PlannerOptions p = o.planner;
  p.safety_margin = std::min(o.squeeze_margin, o.planner.safety_margin);
  return p;
}

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
    case Mode::kYielding: return "yielding";
  }
  return "?";
}

CollisionAvoidance::CollisionAvoidance(const CaOptions& options)
    : options_(options),
      planner_(options.planner),
      squeeze_planner_(squeeze_options(options)),
      map_(options.map),
      track_(options.own_track)
{
}

void CollisionAvoidance::set_targets(const Targets& targets)
{
  // The same goal re-sent (the tour runner does at 2 Hz, re-expressed with the newest
  // localization) with its targets where they were is no reason to plan anew: a replan every
  // 0.5 s flipped the robot between detours left and right of an obstacle, turning on the
  // spot for 15 s. Targets that moved (a loop closure) or a new goal are. Compared with the
  // list last taken as a change, so that small moves do not add up unnoticed.
  bool same = has_targets_ && targets.goal_id != 0 && targets.goal_id == targets_.goal_id &&
              targets.final_is_goal == targets_.final_is_goal && targets.poses.size() == changed_to_.size();
  for (size_t i = 0; same && i < targets.poses.size(); ++i)
    same = (targets.poses[i].translation() - changed_to_[i].translation()).norm() <= options_.resend_tolerance;
  targets_ = targets;
  has_targets_ = !targets.poses.empty();
  if (same) return;
  changed_to_ = targets.poses;
  targets_changed_ = true;
  next_ = 0;
}

void CollisionAvoidance::cancel()
{
  targets_ = Targets{};
  has_targets_ = false;
  targets_changed_ = true;
}

void CollisionAvoidance::on_odometry(time::Time stamp, const Pose2& odom_from_base, double v)
{
  pose_ = odom_from_base;
  v_ = v;
  has_pose_ = true;
  const int64_t us = time::to_utime(stamp);
  // The same encoder sample again (published at the driver's rate with no new sample) adds
  // nothing; out of order or a jump back (a restarted source): start the history anew.
  if (!odometry_.empty() && us == odometry_.back().utime) return;
  if (!odometry_.empty() && us < odometry_.back().utime) odometry_.clear();
  odometry_.push_back({us, odom_from_base});
  while (odometry_.size() > 2 && us - odometry_.front().utime > static_cast<int64_t>(kOdometryKept * 1e6))
    odometry_.pop_front();
}

Pose2 CollisionAvoidance::pose_at(time::Time stamp) const
{
  const auto p = geometry::bracketed_at(odometry_, time::to_utime(stamp), kOdometryGapUs,
                                        [](const OdometrySample& s) { return s.pose; });
  return p ? *p : pose_;
}

void CollisionAvoidance::on_scan(time::Time stamp, const std::vector<PolarReading>& laser_readings, double range_max)
{
  if (!has_pose_) return;
  ScanPoints sp;
  sp.stamp = stamp;
  sp.odom_from_base = pose_at(stamp);
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

bool CollisionAvoidance::may_squeeze(double clearance, double tight) const
{
  const double here = map_.clearance(pose_.translation(), clearance);
  // Under way: on while the body keeps the squeeze margin (scan noise allowed).
  if (squeezing_) return here >= tight - 0.01;
  // Begun only from the full clearance, with nobody near (squeeze_people).
  return here >= clearance && !(options_.squeeze_people > 0.0 && person_within(options_.squeeze_people));
}

bool CollisionAvoidance::person_within(double reach) const
{
  const Eigen::Vector2d here = pose_.translation();
  for (const auto& t : map_.tracker().tracks())
    if (t.moved && !t.centroids.empty() && (t.centroids.back().second - here).norm() <= reach) return true;
  for (const auto& m : map_.tracker().last_seen_movers())
    if ((m.position - here).norm() <= reach) return true;
  return false;
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

bool CollisionAvoidance::beyond_reach(const std::vector<Pose2>& aims) const
{
  return std::any_of(aims.begin(), aims.end(), [&](const Pose2& g) {
    return (g.translation() - pose_.translation()).norm() > options_.max_target_distance;
  });
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
  squeezing_ = false;  // the caller says so after this
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
  // The way the robot came, with the clearance it had (not while it drives back over it).
  if (retrace_.empty()) {
    const double full = options_.planner.robot_radius + options_.planner.safety_margin;
    track_.add(pose_.translation(), map_.clearance(pose_.translation(), full));
  }
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

  // Out of a person's way sideways, until they have passed (yielding.cpp): nothing else decides
  // meanwhile, but a new goal ends it.
  if (auto yielding = yield_under_way(now)) return *yielding;
  // Someone coming through a doorway or a narrow hallway the robot is not yet in (or both are):
  // out of their way before it, not after meeting them in it.
  if (auto before = yield_before_one_lane(now)) return *before;

  // A back-off manoeuvre runs to its end: re-deciding every 100 ms on a clearance that
  // flickers around the threshold (scan noise) made the robot twitch between turning away
  // and turning back. New targets end a plain back-off (the robot decides anew toward them;
  // running every back-off to its end cost the obstacle courses seven of 47 goals, in time).
  // Giving way goes on while the targets are re-sent for the same goal (re-expressed as the
  // localization corrects the odometry, which it does during every turn on the spot): that
  // cut every give-way short in its first turn. A new goal ends it too. Targets re-sent for
  // the same identified goal (goal id not 0: the tour runner re-sends at 2 Hz) are no new
  // targets: they cut every plain back-off short within half a second in the demo.
  const bool same_goal = targets_.goal_id != 0 && targets_.goal_id == backoff_goal_id_;
  const bool keeps_going = giving_way_now_ ? targets_.goal_id == backoff_goal_id_ : (!targets_changed_ || same_goal);
  if (backoff_id_ && active_ && active_->id == *backoff_id_ && keeps_going) {
    const bool ours = has_feedback_ && feedback_.trajectory_id == *backoff_id_;
    const bool ended = ours && (feedback_.state == 2 || feedback_.state == 0);
    // Committed, but never blind: something on what remains of it ends it (on the way back
    // along the robot's track: closer than the robot was there).
    const bool blocked =
        retrace_.empty() ? first_collision(active_->chain, map_, options_.planner.robot_radius + options_.planner.safety_margin,
                                           options_.planner.check_step, ours ? feedback_.progress : 0.0)
                               .has_value()
                         : retrace_blocked();
    if (!ended && !blocked && now < backoff_until_) {
      if (time::to_seconds(now - last_sent_) >= options_.refresh_period) {
        last_sent_ = now;
        return active_;  // keep-alive
      }
      return std::nullopt;
    }
  }
  backoff_id_.reset();
  giving_way_now_ = false;
  retrace_.clear();
  // Giving way goes on until the robot is out of the way: a line that turned out blocked once
  // the turn brought its end into view (the laser looks ahead only) is replaced by the next
  // freest one from where the robot is, instead of heading straight back into the spot.
  if (give_way_active_ && !targets_changed_goal()) {
    const double done = (pose_.translation() - give_way_from_).norm();
    if (done < 0.8 * options_.give_way.length && now < give_way_until_) {
      if (auto again = giving_way(now, options_.give_way.length - done)) return again;
    }
    give_way_active_ = false;
  }

  bool replan = targets_changed_ || !active_ || stopped_ || mode_ == Mode::kReactive || mode_ == Mode::kBlocked ||
                mode_ == Mode::kYielding;
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
    const PlannerOptions& kept = squeezing_ ? squeeze_planner_.options() : options_.planner;
    if (first_collision_near(active_->chain, map_, kept, std::max(0.0, progress - 0.1))) replan = true;
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
  const std::vector<Pose2> aims = goals();
  if (beyond_reach(aims)) return stop(now, Mode::kBlocked, "a target beyond max_target_distance_m: not planned");
  auto planned = planner_.plan(pose_, v_now, aims, map_, targets_.max_speed);
  if (!planned && next_ + 1 < targets_.poses.size()) {
    // The next target cannot be reached from here; the one after may be.
    const size_t keep = next_;
    ++next_;
    const std::vector<Pose2> further = goals();
    if (!beyond_reach(further)) planned = planner_.plan(pose_, v_now, further, map_, targets_.max_speed);
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
  // Nothing keeps the full clearance: a passage the body fits through with squeeze_margin,
  // slowly (a chain, else a detour on the grid). Only to targets with the full clearance
  // (through a narrow place to room beyond, not up to something), and begun only from where
  // the robot has it (closer to something, a person who stepped up to it, it backs off) with
  // nobody near; once in, it goes on (walkers keep the near margin on every chain).
  bool squeeze = false;
  const double tight = options_.planner.robot_radius + squeeze_planner_.options().safety_margin;
  if (!planned && options_.squeeze_margin > 0.0 && may_squeeze(clearance, tight)) {
    auto g = goals();
    while (!g.empty() && map_.clearance(g.back().translation(), clearance) < clearance) g.pop_back();
    const double speed = std::min(targets_.max_speed, options_.squeeze_speed);
    if (!g.empty()) planned = squeeze_planner_.plan(pose_, v_now, g, map_, speed);
    if (!planned && !g.empty()) {
      const bool is_goal = final_goal && next_ + 1 == targets_.poses.size();
      if (auto corners = grid_path(map_, pose_.translation(), g.front().translation(), tight, options_.grid))
        planned = squeeze_planner_.plan_along(pose_, v_now, *corners,
                                              is_goal ? std::optional<double>(g.front().theta()) : std::nullopt, map_, speed);
    }
    squeeze = planned.has_value();
  }
  if (planned) {
    blocked_since_set_ = false;
    ++replans_;
    if (detour) ++detours_;
    status_ = squeeze ? "planned: squeezing through" : detour ? "planned: detour" : "planned";
    auto sent = send_new(std::move(planned->chain), now, planned->predicted_time, Mode::kPlanned);
    squeezing_ = squeeze;
    return sent;
  }
  return reactive(now);
}

}  // namespace rgnav::collision_avoidance
