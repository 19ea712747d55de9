// The fallback layer of CollisionAvoidance (collision_avoidance.h), when no chain to the
// targets is free: backing off from what is too close, giving way to someone who waits for
// the robot (give_way.h), and Holz et al.'s reactive behaviours (reactive.h), all sent as
// short trajectories so the drive stays the only one commanding the base.
#include "collision_avoidance/collision_avoidance.h"

#include <cmath>
#include <iostream>

namespace rgnav::collision_avoidance {

using trajectory::Chain;
using trajectory::Segment;

namespace {
constexpr const char* kTurningAway = "reactive fallback: backing off, turning away";
}  // namespace

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

bool CollisionAvoidance::someone_waits_near(double reach) const
{
  // A mover's track ended near the robot (they stopped: their cells turned static) and
  // something still stands where it ended. A box the robot squeezes past is no reason to
  // drive back a metre; a person waiting for it is.
  constexpr double kPersonRadius = 0.3;  // [m] a track's centroid to the person's far side, generously
  for (const auto& m : map_.tracker().last_seen_movers()) {
    if ((m.position - pose_.translation()).norm() > reach + kPersonRadius) continue;
    if (map_.clearance(m.position, kPersonRadius) < kPersonRadius) return true;
  }
  return false;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::giving_way(time::Time now, double length)
{
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const Eigen::Vector2d here = pose_.translation();
  const auto g = goals();
  const Eigen::Vector2d to_target = g.empty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(g.front().translation() - here);
  const double away = to_target.norm() > 1e-6 ? std::atan2(-to_target.y(), -to_target.x()) : pose_.theta() + M_PI;
  GiveWayOptions o = options_.give_way;
  o.length = length;
  if (o.length < o.min_length) return std::nullopt;
  const auto way = choose_give_way(map_, here, away, clearance, options_.planner.check_step, o);
  if (!way) return std::nullopt;
  const double dth = geometry::normalize_angle(way->heading - pose_.theta());
  const bool turn_first = std::fabs(dth) > 0.05;
  const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
  if (turn_first && !standing) return stop(now, Mode::kReactive, "reactive fallback: no headway, stopping to give way");
  Segment out = Segment::line(Pose2(here, way->heading), way->length);
  out.set_v_max(options_.give_way_speed);
  Chain c = turn_first ? Chain({Segment::turn(pose_, dth), out}) : Chain({out});
  const double t = (turn_first ? trajectory::turn_duration(dth, options_.omega_max, 1.0) : 0.0) +
                   way->length / options_.give_way_speed;
  status_ = "reactive fallback: no headway, yielding: giving way";
  auto sent = commit_backoff(send_new(std::move(c), now, t, Mode::kReactive), now, t);
  giving_way_now_ = true;
  return sent;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::retracing(time::Time now)
{
  if (!options_.retrace_own_track) return std::nullopt;
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const auto way = way_back(track_, map_, pose_.translation(), options_.planner.robot_radius, clearance,
                            options_.own_track);
  if (!way) return std::nullopt;
  const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
  if (!standing) return stop(now, Mode::kReactive, "reactive fallback: no headway, stopping to go back the way it came");
  // Straight legs along the track, turning on the spot at its corners (always safe for the
  // round base): no smoothing, which would leave the track where it is tight.
  Chain c;
  Pose2 from = pose_;
  double t = 0.0;
  for (const auto& corner : way->corners) {
    const Eigen::Vector2d d = corner - from.translation();
    const double dth = geometry::normalize_angle(std::atan2(d.y(), d.x()) - from.theta());
    if (std::fabs(dth) > 1e-3) {
      c.push_back(Segment::turn(from, dth));
      t += trajectory::turn_duration(dth, options_.omega_max, 1.0);
      from = c.end();
    }
    Segment leg = Segment::line(from, d.norm());
    leg.set_v_max(options_.retrace_speed);
    c.push_back(leg);
    t += d.norm() / options_.retrace_speed;
    from = c.end();
  }
  status_ = "reactive fallback: no headway, going back the way it came";
  auto sent = commit_backoff(send_new(std::move(c), now, t, Mode::kReactive), now, t);
  if (sent) {
    retrace_.clear();
    for (size_t i = 0; i < way->points.size(); ++i) retrace_.push_back({way->points[i], way->needs[i]});
    // What it drives back over is no longer the way it came: a second way back from there
    // would lead into the same place again.
    track_.keep_oldest(way->track_index + 1);
  }
  return sent;
}

bool CollisionAvoidance::retrace_blocked() const
{
  // The points not yet passed: from the one nearest to the robot on.
  size_t nearest = 0;
  for (size_t i = 1; i < retrace_.size(); ++i)
    if ((retrace_[i].at - pose_.translation()).norm() < (retrace_[nearest].at - pose_.translation()).norm()) nearest = i;
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  for (size_t i = nearest + 1; i < retrace_.size(); ++i)
    if (map_.clearance(retrace_[i].at, clearance) < retrace_[i].need) return true;
  return false;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::commit_backoff(std::optional<trajectory::Trajectory> t,
                                                                         time::Time now, double duration)
{
  if (t) {
    backoff_id_ = t->id;
    backoff_goal_id_ = targets_.goal_id;
    giving_way_now_ = false;  // giving_way() says so after this
    // Its predicted duration plus the acceleration phases and some slack; then decide anew.
    backoff_until_ = now + time::Duration(static_cast<int64_t>((duration + 2.0) * 1e6));
  }
  return t;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::send_reactive_turn(double angle, time::Time now,
                                                                            const std::string& why)
{
  const double t = trajectory::turn_duration(angle, options_.omega_max, 1.0);
  status_ = why;
  auto sent = send_new(Chain({Segment::turn(pose_, angle)}), now, t, Mode::kReactive);
  if (sent) {
    reactive_turn_id_ = sent->id;
    // Its predicted duration plus the acceleration phases and some slack.
    reactive_turn_until_ = now + time::Duration(static_cast<int64_t>((t + 1.0) * 1e6));
  }
  return sent;
}

std::optional<std::optional<trajectory::Trajectory>> CollisionAvoidance::reactive_turn_under_way(time::Time now)
{
  if (!reactive_turn_id_) return std::nullopt;
  const bool current = active_ && active_->id == *reactive_turn_id_ && !stopped_ && mode_ == Mode::kReactive;
  const bool ours = has_feedback_ && feedback_.trajectory_id == *reactive_turn_id_;
  const bool ended = ours && (feedback_.state == 2 || feedback_.state == 0);
  if (!current || ended || now >= reactive_turn_until_) {
    reactive_turn_id_.reset();
    return std::nullopt;
  }
  if (time::to_seconds(now - last_sent_) >= options_.refresh_period) {
    last_sent_ = now;
    return active_;  // keep-alive
  }
  return std::optional<trajectory::Trajectory>();
}

std::optional<trajectory::Trajectory> CollisionAvoidance::reactive(time::Time now)
{
  ++fallbacks_;
  // A turn decided below runs to its end: deciding anew 100 ms later, the stop-and-wait at
  // the top cut every "turn toward the target" short, and the robot stood facing away from
  // its target for minutes (a demo stuck in a doorway), turning and stopping every 1.5 s.
  if (auto turning = reactive_turn_under_way(now)) return *turning;
  const Pose2 target = goals().empty() ? pose_ : goals().front();
  const Eigen::Vector2d d = pose_.inverse() * target.translation();
  const double bearing = std::atan2(d.y(), d.x());
  const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
  if (!blocked_since_set_) {
    blocked_since_set_ = true;
    blocked_since_ = now;
  }
  // Someone in the way whose way the robot blocks in turn (a doorway, a narrow hallway: no chain
  // gets past them): out of their path sideways, until they have passed (give_way.h). Not at
  // once: someone crossing clears the way by themselves within the first wait. Meanwhile stand:
  // backing off or turning away from them now would only turn the laser from them.
  if (now >= yield_retry_after_) {
    if (const auto person = person_in_the_way()) {
      // Walking straight at the robot along its way, they will not pass by: no reason to wait
      // and see; someone who stopped there may walk on by themselves.
      const double after = person->walking ? options_.yield_head_on_after : options_.yield_sideways_after;
      if (time::to_seconds(now - progress_since_) >= after) {
        auto out = start_yield(now, person->path);
        if (yield_.phase != YieldPhase::kNone) return out;
      } else {
        return stop(now, Mode::kReactive, "reactive fallback: someone in the way, waiting");
      }
    }
  }
  // No headway for a long time: whoever waits with the robot (a person at their personal
  // space, who will not walk on while the robot stands in their way) gets room. Back away
  // from what is near, farther out than the plain back-off looks.
  if (time::to_seconds(now - progress_since_) > options_.yield_after) {
    progress_since_ = now;
    // Give way from where the robot got stuck, not from wherever it waits next: a person
    // walking back and forth across its way (no waiting involved) kept it yielding every
    // yield_after, a metre back each time, back to the start of the course. And not while
    // someone walks near by: they pass on their own.
    const double reach = options_.planner.robot_radius + options_.planner.safety_margin + options_.yield_reach;
    const Eigen::Vector2d here = pose_.translation();
    if (!has_yield_anchor_ || time::to_seconds(now - yield_anchor_time_) > options_.give_way_timeout ||
        (here - yield_anchor_).norm() > 2.0 * options_.give_way.length) {
      has_yield_anchor_ = true;
      yield_anchor_ = here;
      yield_anchor_time_ = now;
    }
    const double left = options_.give_way.length - (here - yield_anchor_).norm();
    const bool someone_walking = map_.clearance_predicted(here, reach) < reach;
    if (!someone_walking && someone_waits_near(reach)) {
      if (auto back = giving_way(now, left)) {
        give_way_active_ = true;
        give_way_from_ = yield_anchor_;
        give_way_goal_id_ = targets_.goal_id;
        give_way_until_ = now + time::Duration(static_cast<int64_t>(options_.give_way_timeout * 1e6));
        return back;
      }
    }
    // Stuck where the robot drove in: back the way it came. Backing away from what is near
    // wants the full clearance, which the way in may never have had.
    if (auto back = retracing(now)) return back;
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
    return send_reactive_turn(dec.heading, now, "reactive fallback: turning toward free space");
  }
  // Free space leads away from the target (back down the corridor the robot came along):
  // driving there only loses ground. Face the target's side and plan again from there.
  if (dec.action == ReactiveDecision::Action::kDrive &&
      std::fabs(geometry::normalize_angle(dec.heading - bearing)) > M_PI_2) {
    if (!standing) return stop(now, Mode::kReactive, "reactive fallback: free space leads away, stopping");
    const double turn = std::clamp(bearing, -options_.reactive.max_turn, options_.reactive.max_turn);
    // Once it faces that side, wait again before the next try (people there may walk on).
    blocked_since_ = now + time::Duration(static_cast<int64_t>(trajectory::turn_duration(turn, options_.omega_max, 1.0) * 1e6));
    return send_reactive_turn(turn, now, "reactive fallback: turning toward the target");
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
