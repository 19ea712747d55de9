// Leaving a person's path sideways (give_way.h), the part of CollisionAvoidance
// (collision_avoidance.h) that runs it: who is in the way, the way out of their path and the
// wait beside it, in phases (looking behind when nothing around is known, leaving, waiting),
// each sent as a trajectory so the drive stays the only one commanding the base.
#include <algorithm>
#include <cmath>
#include <limits>

#include "collision_avoidance/collision_avoidance.h"
#include "trajectory/construct.h"

namespace rgnav::collision_avoidance {

using trajectory::Chain;
using trajectory::Segment;

namespace {

constexpr const char* kLeaving = "yielding: leaving the person's path sideways";
constexpr const char* kWaitingThere = "yielding: beside the person's path, waiting for them to pass";
constexpr const char* kLooking = "yielding: turning to look for room behind";
constexpr const char* kReturning = "yielding: they passed, back to where it left its way";
constexpr int kMaxPlans = 10;  // yield points chosen anew when the way there turns out blocked (or much longer)
constexpr double kRecheck = 1.0;     // [s] leaving: how often to look for a nearer place out of the way
constexpr double kMuchNearer = 1.0;  // [m] ... this much nearer than what is left of the way
constexpr double kAhead = 1.05;  // [rad] someone in the way stands within this of the way to the target
// A mover counts as a person once it moved this long while the robot held its heading
// (people_tracker.h Track::moving_steady: walls coming into view as the robot turns move too).
constexpr double kSteadyWalking = 0.3;  // [s] walking now
constexpr double kSteadyStopped = 0.5;  // [s] walked up and stopped
constexpr double kReturnMargin = 0.02;  // [m] the way back keeps this beyond the clearance
// [m] the yield's manoeuvres count as blocked this much short of the clearance only: the
// searches' legs graze the clearance (a detour's first leg from a tight spot keeps the clearance
// of its start), and the scans on the way place a wall a few millimetres off; the safety margin
// (0.1 m) is for what moves, and the yield waits for that
constexpr double kGraze = 0.02;
// [m] ... and going back into the way it left (a hallway): this much. What the map remembers of
// walls seen before two turns on the spot sits where the odometry, bent by them, held it then:
// a hallway looks narrower than it is by centimetres (the newest scans place it right).
constexpr double kGrazeBack = 0.05;
constexpr int kMaxReturns = 4;  // ways back chosen anew when blocked
constexpr double kOnTheWay = 1.0;  // [m] where the yield began, this near the targets' polyline: back to it there
constexpr double kSameWay = 0.1;  // [rad] a track's way since it began, near its velocity's
constexpr double kHeadOn = 0.5;   // [rad] walking within this of straight down the robot's way, backwards (people crossing it, or two of them passing each other in the tracker, are not)
constexpr double kOffTheWay = 0.5;  // [m] ... and this much farther from it than a path is wide, still on it
constexpr double kWayAhead = 1.0;   // [m] the robot's way: toward its first target at least this far
constexpr double kPersonRadius = 0.3;  // [m] a person's points lie this close to their track's centroid
constexpr double kApart = 0.3;         // [m] beams beside a person reach this much farther
constexpr double kOneLaneStep = 0.15;  // [m] a one-lane stretch this near the robot (the person) along the line: in it

// Straight legs through `corners`, then a turn to `final_heading`. Without `kappa`, a turn on the
// spot before every leg: a synchro drive can always do this from standing, and the legs are the
// search's free lines. With it, the corners between two legs are rounded (smooth_turn, curvature
// kappa: the drive goes on through them) where both legs are long enough; the first turn (from
// standing) and the last stay turns on the spot. A person following the robot out of their way,
// or waiting for it there, waits behind a robot that keeps driving away; at every stop for a turn
// on the spot their patience runs (at a hallway's mouth, they turned back for good).
Chain polyline(const Pose2& start, const std::vector<Eigen::Vector2d>& corners, double final_heading, double v_max,
               std::optional<double> kappa = std::nullopt)
{
  std::vector<Eigen::Vector2d> points;
  for (const auto& corner : corners)
    if ((corner - (points.empty() ? start.translation() : points.back())).norm() >= 1e-3) points.push_back(corner);
  Chain c;
  Pose2 from = start;
  bool rounded_in = false;  // the last corner was rounded: `from` already heads along this leg
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d d = points[i] - from.translation();
    if (!rounded_in) {
      const double dth = geometry::normalize_angle(std::atan2(d.y(), d.x()) - from.theta());
      if (std::fabs(dth) > 1e-3) {
        c.push_back(Segment::turn(from, dth));
        from = c.end();
      }
    }
    double leg = d.norm();
    // Round the corner at points[i] toward points[i + 1]: the turn's tangent lengths (from where
    // it begins to the corner, from the corner to where it ends) must fit on both legs.
    // (Nearly reversing corners stay turns on the spot: the rounded turn would swing wide.)
    std::optional<Chain> turn;
    if (kappa && i + 1 < points.size()) {
      const Eigen::Vector2d out = points[i + 1] - points[i];
      const double dth = geometry::normalize_angle(std::atan2(out.y(), out.x()) - from.theta());
      if (std::fabs(dth) > 0.05 && std::fabs(dth) < 2.5) {
        Chain shape = trajectory::smooth_turn(Pose2(), dth, *kappa);
        const Pose2 e = shape.end();
        const double before = e.x() - e.y() / std::tan(dth);
        const double after = e.y() / std::sin(dth);
        if (before > 0.0 && after > 0.0 && before <= leg - 0.05 && after <= out.norm() - 0.05) {
          leg -= before;
          turn = std::move(shape);
        }
      }
    }
    if (leg > 1e-3) {
      Segment line = Segment::line(from, leg);
      line.set_v_max(v_max);
      c.push_back(line);
      from = c.end();
    }
    rounded_in = turn.has_value();
    if (turn) {
      for (Segment seg : turn->segments()) {
        seg.set_v_max(v_max);
        c.append_at_end(seg);
      }
      // The turn ends on the line to the next corner, heading along it (up to rounding): the
      // next leg starts there, no turn on the spot before it.
      const Eigen::Vector2d next = points[i + 1] - c.end().translation();
      from = Pose2(c.end().translation(), std::atan2(next.y(), next.x()));
    }
  }
  const double dth = geometry::normalize_angle(final_heading - from.theta());
  if (std::fabs(dth) > 1e-3) c.push_back(Segment::turn(c.empty() ? from : c.end(), dth));
  return c;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// first_collision's rule from s0 on, on what is there now: where someone is only predicted to
// walk does not count. The person the robot makes way for follows it down their path, and
// their prediction runs ahead of them into the way out (and the way back).
bool blocked_now(const LocalMap& map, const Chain& c, double s0, double clearance, double step)
{
  // Leaving a tight spot as first_collision lets a chain (and the search chose the way): from
  // the clearance there with everything counted.
  const double c0 = map.clearance(c.pose_at(s0).translation(), clearance);
  for (double s = s0; s <= c.length() + 1e-9; s += step)
    if (map.clearance_observed(c.pose_at(s).translation(), clearance) < required_clearance(clearance, c0, s - s0))
      return true;
  return false;
}

// The way someone walks (unit): where their track went since it began, over a metre or more
// and within a few degrees of their velocity's direction (a velocity fit over half a second
// sways a little); else the velocity (where the track began, they may have walked another way:
// toward a door from the side).
Eigen::Vector2d walking_direction(const Eigen::Vector2d& velocity, const Eigen::Vector2d& since_first)
{
  const Eigen::Vector2d v = velocity.normalized();
  if (since_first.norm() >= 1.0 && since_first.normalized().dot(v) > std::cos(kSameWay)) return since_first.normalized();
  return v;
}

}  // namespace

std::optional<CollisionAvoidance::PersonInTheWay> CollisionAvoidance::person_in_the_way() const
{
  const Eigen::Vector2d here = pose_.translation();
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const YieldOptions& yo = options_.give_way.yield;
  // The robot is on their path: within what the path keeps free of its centre line.
  const double on_path = clearance + yo.path_half_width;
  // In the robot's way: ahead, toward its next target (a wall seen anew as the robot turns can
  // look like someone who walked up and stopped; behind the robot it blocks nothing).
  const auto g = goals();
  const Eigen::Vector2d to_target = g.empty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(g.front().translation() - here);
  const std::optional<Eigen::Vector2d> way = way_ahead();
  if (!way || to_target.norm() < 1e-6) return std::nullopt;
  std::optional<PersonInTheWay> best;
  double best_d = 0.0;
  // Only someone coming the other way along the robot's way: in a doorway or a hallway they
  // cannot pass each other. Someone crossing it passes by (the robot waits a moment, as it
  // always did), and who else stops in front of it is left to the older fallbacks.
  // speed: walking at it now (0: walked up and stopped).
  auto consider = [&](const Eigen::Vector2d& at, Eigen::Vector2d dir, double speed) {
    const Eigen::Vector2d to_robot = here - at;
    const double d = to_robot.norm();
    if (d < 1e-6 || -to_robot.dot(to_target) < std::cos(kAhead) * d * to_target.norm()) return;
    if (dir.dot(*way) >= -std::cos(kHeadOn) * dir.norm()) return;
    // Through a doorway or a hallway the robot's way runs along, theirs does too (one lane;
    // where they came from, they may have walked toward it from the side, and a few degrees put
    // the yield point decimetres off down the path). Their path: the robot's way backwards,
    // from abreast of them.
    if (std::fabs(cross(*way, -to_robot)) > on_path + kOffTheWay) return;
    if (best && d >= best_d) return;
    PersonInTheWay p;
    p.path.from = here + *way * way->dot(-to_robot);
    p.path.direction = -*way;
    p.walking = speed > 0.0;
    p.at = at;
    p.speed = speed;
    best = p;
    best_d = d;
  };
  const double min_speed = options_.map.people.min_speed;
  for (const Track& t : map_.tracker().tracks()) {
    if (!t.moved || t.moving_steady < kSteadyWalking || t.centroids.empty() || t.velocity.norm() < min_speed) continue;
    const Eigen::Vector2d at = t.centroids.back().second;
    if ((at - here).norm() > options_.yield_notice) continue;
    // Where the newest scan sees it, apart from what is behind it: a piece of wall that seems
    // to slide along the wall as the robot turns or drives (the part in view changes) is not.
    if (map_.seen_now(at) == SeenNow::kStillThere && !map_.stands_apart(at, kPersonRadius, kApart)) continue;
    consider(at, walking_direction(t.velocity, at - t.first), t.velocity.norm());
  }
  // Someone who walked up and stopped (their cells turned static, the track ended), and still
  // stands there: they were walking the way they last moved.
  for (const auto& m : map_.tracker().last_seen_movers()) {
    if ((m.position - here).norm() > options_.yield_notice_stopped || m.moving_steady < kSteadyStopped) continue;
    // Still there: the newest scan ends at them (a remembered one may have walked on unseen),
    // and apart from what is behind them (not a piece of wall that a person walking past hid
    // for a moment: it reappears piece by piece, and looks like someone who walked and stopped).
    if (map_.seen_now(m.position) != SeenNow::kStillThere || !map_.stands_apart(m.position, kPersonRadius, kApart))
      continue;
    if (m.walking.norm() < min_speed) continue;
    consider(m.position, walking_direction(m.walking, m.position - m.first), 0.0);
  }
  return best;
}

std::optional<std::optional<trajectory::Trajectory>> CollisionAvoidance::yield_before_one_lane(time::Time now)
{
  const Eigen::Vector2d here = pose_.translation();
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  bool meeting = false;
  std::optional<PersonInTheWay> person;
  if (now >= yield_retry_after_) person = person_in_the_way();
  if (person && person->walking) {
    // Too narrow to pass each other: less than the robot's clearance either side beside a
    // person passing (the width of their predicted path).
    const double width = 2.0 * (clearance + options_.give_way.yield.path_half_width);
    if (const auto lane = one_lane_between(map_, here, person->at, width, kPersonRadius)) {
      const bool robot_in = lane->begin < kOneLaneStep;
      const bool person_in = lane->length - lane->end < kOneLaneStep;
      if (person_in) {
        meeting = true;  // they were there first (or both are in it: they meet there)
      } else if (!robot_in) {
        // Neither is in it yet: does the robot get out of it before they get in? It drives the
        // open space before it at the targets' speed, between walls that close at the planner's
        // slow speed, until its clearance is beyond the far end.
        const double robot_out = lane->begin / std::max(0.05, targets_.max_speed) +
                                 (lane->end - lane->begin + clearance) / options_.planner.slow_speed;
        const double person_there = (lane->length - lane->end) / person->speed;
        meeting = person_there < robot_out;
      }
      // The robot in it and they not yet: it was there first, and goes on through.
    }
  }
  if (!meeting) {
    one_lane_meeting_ = false;
    return std::nullopt;
  }
  if (!one_lane_meeting_) {
    one_lane_meeting_ = true;
    one_lane_since_ = now;
  }
  // As in the fallback: the reason holds a moment (not one scan's glimpse of a track).
  if (time::to_seconds(now - one_lane_since_) < options_.yield_head_on_after) return std::nullopt;
  one_lane_meeting_ = false;
  auto out = start_yield(now, person->path);
  if (yield_.phase == YieldPhase::kNone) return std::nullopt;  // no place out of their way: as before
  return std::optional<std::optional<trajectory::Trajectory>>(std::move(out));
}

double CollisionAvoidance::manoeuvre_time(const trajectory::Chain& c) const
{
  // As the drive runs it: its velocity profile (stopping at every turn on the spot).
  trajectory::Limits lim = options_.planner.limits;
  lim.v_max = std::min(lim.v_max, options_.yield_speed);
  return trajectory::VelocityProfile::compute(c, lim, 0.0, 0.0, 0.05).total_time();
}

std::optional<Eigen::Vector2d> CollisionAvoidance::way_ahead() const
{
  const Eigen::Vector2d here = pose_.translation();
  for (size_t i = next_; i < targets_.poses.size(); ++i) {
    const Eigen::Vector2d d = targets_.poses[i].translation() - here;
    if (d.norm() >= kWayAhead || i + 1 == targets_.poses.size())
      return d.norm() > 1e-6 ? std::optional<Eigen::Vector2d>(d.normalized()) : std::nullopt;
  }
  return std::nullopt;
}

std::optional<trajectory::Trajectory> CollisionAvoidance::start_yield(time::Time now, const PersonPath& path)
{
  yield_ = Yield{};
  yield_.phase = YieldPhase::kLeaving;
  yield_.path = path;
  yield_.goal_id = targets_.goal_id;
  yield_.goal_at = targets_.poses.back().translation();
  yield_.since = now;
  yield_.trail = {pose_.translation()};
  yield_.start_heading = pose_.theta();
  yield_.until = now + time::Duration(static_cast<int64_t>(options_.yield_timeout * 1e6));
  ++yields_;
  return leave_path(now);
}

std::optional<trajectory::Trajectory> CollisionAvoidance::leave_path(time::Time now)
{
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const Eigen::Vector2d here = pose_.translation();
  const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
  yield_.trajectory_id = 0;
  yield_.since = now;
  if (!standing) {
    yield_.phase = YieldPhase::kLeaving;
    return stop(now, Mode::kYielding, "yielding: stopping to leave the person's path");
  }
  // Where they are now (they walk on while the robot turns and stops): their path from there.
  if (const auto person = person_in_the_way()) yield_.path = person->path;
  const auto y = ++yield_.plans <= kMaxPlans ? choose_yield_point(map_, here, yield_.path, clearance, options_.give_way.yield)
                                              : std::nullopt;
  if (!y) {
    if (yield_.looked || yield_.plans > kMaxPlans) {
      end_yield(now, false);
      return std::nullopt;
    }
    // Nothing known behind the robot (the laser looks ahead): face the way down the person's
    // path, away from them, where a hallway's mouth and the room behind it are, and search again.
    yield_.looked = true;
    yield_.phase = YieldPhase::kLooking;
    const double heading = std::atan2(yield_.path.direction.y(), yield_.path.direction.x());
    const double dth = geometry::normalize_angle(heading - pose_.theta());
    const double t = trajectory::turn_duration(dth, options_.omega_max, 1.0);
    yield_.phase_until = now + time::Duration(static_cast<int64_t>((t + 2.0) * 1e6));
    status_ = kLooking;
    auto sent = send_new(Chain({Segment::turn(pose_, dth)}), now, t, Mode::kYielding);
    if (sent) yield_.trajectory_id = sent->id;
    return sent;
  }
  yield_.point = y->point;
  // There, face where the person comes from: the laser then sees them come and pass.
  const Eigen::Vector2d look = yield_.path.from - y->point;
  const double facing = look.norm() > 1e-6 ? std::atan2(look.y(), look.x()) : pose_.theta();
  if (y->corners.empty()) {
    yield_.phase = YieldPhase::kWaiting;
    return stop(now, Mode::kYielding, kWaitingThere);
  }
  Chain c = polyline(pose_, y->corners, facing, options_.yield_speed, options_.planner.kappa_max);
  // Rounded corners cut them: where that grazes something, turns on the spot.
  if (first_collision(c, map_, clearance, options_.planner.check_step))
    c = polyline(pose_, y->corners, facing, options_.yield_speed);
  if (auto hit = first_collision(c, map_, clearance, options_.planner.check_step)) {
    end_yield(now, false);
    return std::nullopt;
  }
  const double t = manoeuvre_time(c);
  yield_.phase = YieldPhase::kLeaving;
  yield_.phase_until = now + time::Duration(static_cast<int64_t>((t + 3.0) * 1e6));
  status_ = kLeaving;
  auto sent = send_new(std::move(c), now, t, Mode::kYielding);
  if (sent) yield_.trajectory_id = sent->id;
  return sent;
}

std::optional<std::optional<trajectory::Trajectory>> CollisionAvoidance::yield_under_way(time::Time now)
{
  if (yield_.phase == YieldPhase::kNone) return std::nullopt;
  // A new goal, or (goals without an id) targets moved elsewhere: decide anew.
  const bool other_goal = targets_.goal_id != yield_.goal_id ||
                          (targets_.goal_id == 0 && (targets_.poses.back().translation() - yield_.goal_at).norm() > 0.5);
  if (other_goal || now >= yield_.until) {
    end_yield(now, true);
    return std::nullopt;
  }
  if ((yield_.phase == YieldPhase::kLooking || yield_.phase == YieldPhase::kLeaving) &&
      (pose_.translation() - yield_.trail.back()).norm() > 0.1)
    yield_.trail.push_back(pose_.translation());
  const bool ours = yield_.trajectory_id != 0 && has_feedback_ && feedback_.trajectory_id == yield_.trajectory_id;
  const bool ended = ours && (feedback_.state == 2 || feedback_.state == 0);
  auto keep_alive = [&]() -> std::optional<trajectory::Trajectory> {
    if (time::to_seconds(now - last_sent_) < options_.refresh_period) return std::nullopt;
    last_sent_ = now;
    return active_;
  };
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  switch (yield_.phase) {
    case YieldPhase::kLooking:
      // Done looking as soon as the turn brings a way out into view.
      if (ended || now >= yield_.phase_until ||
          choose_yield_point(map_, pose_.translation(), yield_.path, clearance, options_.give_way.yield))
        return leave_path(now);
      return keep_alive();
    case YieldPhase::kLeaving: {
      if (yield_.trajectory_id == 0) return leave_path(now);  // stopping first
      if (ended) {  // there, and turned to watch the path
        yield_.phase = YieldPhase::kWaiting;
        yield_.since = now;
        status_ = kWaitingThere;
        return std::optional<trajectory::Trajectory>();
      }
      // Committed, but never blind: something on what remains of it (it came into view as the
      // robot turned, someone stepped into it), or the drive stuck: choose again from here.
      // And the view opens on the way (out of a hallway's mouth, the room beside it): a place
      // out of the way much nearer than the one it heads for is worth a stop.
      bool nearer = false;
      if (time::to_seconds(now - yield_.rechecked) >= kRecheck && active_) {
        yield_.rechecked = now;
        const double left = active_->chain.length() - (ours ? feedback_.progress : 0.0);
        const auto y = choose_yield_point(map_, pose_.translation(), yield_.path, clearance, options_.give_way.yield);
        nearer = y && y->travel + kMuchNearer < left;
      }
      if (nearer || yield_way_blocked() || now >= yield_.phase_until) {
        const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
        if (standing) return leave_path(now);
        yield_.trajectory_id = 0;  // stopping first, then choose again
        return stop(now, Mode::kYielding, nearer ? "yielding: a place nearer out of the way, stopping"
                                                 : "yielding: the way out is blocked, stopping");
      }
      return keep_alive();
    }
    case YieldPhase::kWaiting: {
      const Eigen::Vector2d here = pose_.translation();
      const ToPass to_pass = someone_to_pass(map_, yield_.path, here, options_.give_way.yield);
      if (to_pass != ToPass::kNobody) {
        yield_.clear = false;
      } else if (!yield_.clear) {
        yield_.clear = true;
        yield_.clear_since = now;
      }
      if (to_pass != ToPass::kStanding) {
        yield_.standing = false;
      } else if (!yield_.standing) {
        yield_.standing = true;
        yield_.standing_since = now;
      }
      const bool passed = yield_.clear && time::to_seconds(now - yield_.clear_since) >= options_.pass_settle;
      // Someone stands there and does not come (they wait for the robot in turn, or stand aside
      // for it): go if a chain gets past them.
      const bool invited = yield_.standing && time::to_seconds(now - yield_.standing_since) >= options_.standing_go_after &&
                           planner_.plan(pose_, 0.0, goals(), map_, targets_.max_speed).has_value();
      if (passed) {
        if (auto back = return_to_way(now)) return back;
        end_yield(now, true);
        return std::nullopt;
      }
      if (invited || time::to_seconds(now - yield_.since) >= options_.yield_wait_timeout) {
        end_yield(now, true);
        return std::nullopt;
      }
      return stop(now, Mode::kYielding, kWaitingThere);
    }
    case YieldPhase::kReturning:
      // There: the planner goes on from its way. Something in the way back (the scans on the
      // way place the walls of a narrow hallway a little off from where the odometry held
      // them): choose the way back again from here, a few times; then the planner decides.
      if (ended || now >= yield_.phase_until) {
        end_yield(now, true);
        return std::nullopt;
      }
      if ((active_ && active_->chain.empty()) || yield_way_blocked()) {  // stopped for it, or it is there
        if (yield_.returns < kMaxReturns) {
          const bool standing = std::fabs(has_feedback_ ? feedback_.v_cmd : v_) < 0.02;
          if (!standing) return stop(now, Mode::kYielding, "yielding: the way back is blocked, stopping");
          ++yield_.returns;
          if (auto again = return_to_way(now)) return again;
        }
        end_yield(now, true);
        return std::nullopt;
      }
      return keep_alive();
    case YieldPhase::kNone: break;
  }
  return std::nullopt;
}

bool CollisionAvoidance::yield_way_blocked() const
{
  if (!active_) return false;
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin;
  const bool ours = has_feedback_ && feedback_.trajectory_id == active_->id;
  const double graze = yield_.phase == YieldPhase::kReturning ? kGrazeBack : kGraze;
  return blocked_now(map_, active_->chain, ours ? feedback_.progress : 0.0, clearance - graze, options_.planner.check_step);
}

std::optional<trajectory::Trajectory> CollisionAvoidance::return_to_way(time::Time now)
{
  // Back to where it left its way, heading as it was: in a hallway that is back in, lined up;
  // the planner goes on from there (or from wherever this stops). Not along the trail as
  // recorded: two turns on the spot since shift what the odometry frame holds by decimetres at
  // a metre, and a narrow hallway has centimetres to spare. A detour on the map as it is now,
  // to the nearest place there with the clearance.
  // A little more than the clearance: the search's legs graze it, and the drive's check of what
  // the scans add on the way must not find them a millimetre short.
  const double clearance = options_.planner.robot_radius + options_.planner.safety_margin + kReturnMargin;
  const Eigen::Vector2d here = pose_.translation();
  // Where it left its way, as its way is now: the targets follow the localization, the trail
  // the odometry, which two turns on the spot have bent by degrees (decimetres, metres away).
  Eigen::Vector2d goal = yield_.trail.front();
  double heading = yield_.start_heading;
  double nearest = std::numeric_limits<double>::infinity();
  const auto& way = targets_.poses;
  for (size_t i = 0; i + 1 < way.size(); ++i) {
    const Eigen::Vector2d a = way[i].translation(), ab = way[i + 1].translation() - a;
    if (ab.norm() < 1e-6) continue;
    const Eigen::Vector2d p = a + ab * std::clamp((yield_.trail.front() - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    if ((p - yield_.trail.front()).norm() < nearest) {
      nearest = (p - yield_.trail.front()).norm();
      goal = p;
      heading = std::atan2(ab.y(), ab.x());
    }
  }
  if (nearest > kOnTheWay) {
    goal = yield_.trail.front();
    heading = yield_.start_heading;
  }
  if ((goal - here).norm() < 0.3) return std::nullopt;
  double best = map_.clearance(goal, clearance + 0.1);
  const Eigen::Vector2d from = goal;
  for (double r = 0.05; r <= 0.2 + 1e-9 && best < clearance; r += 0.05)
    for (int k = 0; k < 16; ++k) {
      const Eigen::Vector2d p = from + r * Eigen::Vector2d(std::cos(k * M_PI / 8.0), std::sin(k * M_PI / 8.0));
      const double c = map_.clearance(p, clearance + 0.1);
      if (c > best) {
        best = c;
        goal = p;
      }
    }
  if (best < clearance) return std::nullopt;
  const auto corners = way_to(map_, here, goal, clearance, options_.give_way.yield);
  if (!corners) return std::nullopt;
  Chain c = polyline(pose_, *corners, heading, options_.yield_speed, options_.planner.kappa_max);
  if (blocked_now(map_, c, 0.0, clearance - kReturnMargin - kGrazeBack, options_.planner.check_step))
    c = polyline(pose_, *corners, heading, options_.yield_speed);
  if (blocked_now(map_, c, 0.0, clearance - kReturnMargin - kGrazeBack, options_.planner.check_step)) return std::nullopt;
  const double t = manoeuvre_time(c);
  yield_.phase = YieldPhase::kReturning;
  yield_.since = now;
  yield_.phase_until = now + time::Duration(static_cast<int64_t>((t + 3.0) * 1e6));
  status_ = kReturning;
  auto sent = send_new(std::move(c), now, t, Mode::kYielding);
  if (sent) yield_.trajectory_id = sent->id;
  return sent;
}

void CollisionAvoidance::end_yield(time::Time now, bool done)
{
  yield_.phase = YieldPhase::kNone;
  if (!done) {
    yield_retry_after_ = now + time::Duration(static_cast<int64_t>(options_.yield_after * 1e6));
    return;
  }
  // The headway clock starts again from here: the time spent out of the way is no lack of it.
  has_progress_pose_ = true;
  progress_pose_ = pose_.translation();
  progress_since_ = now;
  blocked_since_set_ = false;
  give_way_active_ = false;
}

}  // namespace rgnav::collision_avoidance
