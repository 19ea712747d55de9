#include "sim/people.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::sim {

People::People(std::vector<Person> people, Rng rng)
    : people_(std::move(people)), state_(people_.size()), rng_(rng)
{
  for (size_t i = 0; i < people_.size(); ++i) {
    const auto& p = people_[i];
    state_[i].patience = p.patience;
    std::vector<double> cum{0.0};
    for (size_t k = 1; k < p.path.size(); ++k) cum.push_back(cum.back() + (p.path[k] - p.path[k - 1]).norm());
    if (p.loop && p.path.size() > 1) cum.push_back(cum.back() + (p.path.front() - p.path.back()).norm());
    cumulative_.push_back(std::move(cum));
  }
}

const char* to_string(EncounterChoice c)
{
  switch (c) {
    case EncounterChoice::kWait: return "wait";
    case EncounterChoice::kStandAside: return "stand aside";
    case EncounterChoice::kGoAround: return "go around";
  }
  return "?";
}

Vec2 People::position(size_t i, double s) const
{
  const auto& p = people_[i];
  const auto& cum = cumulative_[i];
  const double length = cum.back();
  if (p.path.size() < 2 || length <= 0.0) return p.path.front();
  // Once: from the start to the end. Loop: wrap around. Back and forth: fold the walk onto
  // [0, length]. Someone who turned back walks s down, below 0 too: the same folds.
  if (p.once) {
    s = std::clamp(s, 0.0, length);
  } else if (p.loop) {
    s = std::fmod(s, length);
    if (s < 0.0) s += length;
  } else {
    s = std::fmod(s, 2.0 * length);
    if (s < 0.0) s += 2.0 * length;
    if (s > length) s = 2.0 * length - s;
  }
  size_t k = 1;
  while (k + 1 < cum.size() && cum[k] < s) ++k;
  const Vec2& a = p.path[k - 1];
  const Vec2& b = k < p.path.size() ? p.path[k] : p.path.front();
  const double leg = cum[k] - cum[k - 1];
  const double u = leg > 0.0 ? (s - cum[k - 1]) / leg : 0.0;
  return a + u * (b - a);
}

namespace {
constexpr double kPassMargin = 0.25;  // [m] beyond touching: how close people pass a robot they walk around
constexpr double kSideSpeed = 0.5;    // sideways steps at this share of the walking speed
constexpr double kWallMargin = 0.03;  // [m] people keep this much from walls and furniture
// Standing aside: people step off their path far enough that the robot passes them this far off
// (surface to surface) and keeps kRobotRoom from the walls, up to kMaxAside.
constexpr double kAsidePass = 0.25;   // [m]
constexpr double kRobotRoom = 0.15;   // [m]
constexpr double kMaxAside = 1.5;     // [m]
// Standing aside ends when the robot is behind them, or this far away (it went elsewhere).
constexpr double kRobotGone = 4.0;    // [m]
// Walking once, turned back and at the start again: they stand this long before they try again.
constexpr double kTryAgainAfter = 3.0;  // [s]
// The robot's velocity is smoothed over this (the physics steps are short).
constexpr double kRobotVelocityTau = 0.2;  // [s]
// Driving away from someone at least this fast, the robot makes way for them.
constexpr double kMakingWay = 0.1;  // [m/s]
}  // namespace

void People::advance(double dt, const std::optional<Circle>& robot_or_none, const StaticClearance& clearance)
{
  time_ += dt;
  if (robot_or_none && dt > 0.0) {
    if (robot_was_) {
      const double a = std::min(1.0, dt / kRobotVelocityTau);
      robot_velocity_ = (1.0 - a) * robot_velocity_ + a * (robot_or_none->center - *robot_was_) / dt;
    }
    robot_was_ = robot_or_none->center;
  }
  for (size_t i = 0; i < people_.size(); ++i) {
    auto& st = state_[i];
    const auto& p = people_[i];
    if (st.waited < p.start_delay) {
      st.waited += dt;
      continue;
    }
    if (st.resting > 0.0) {
      st.resting -= dt;
      continue;
    }
    double next_s = st.s + st.dir * p.speed * dt;
    if (p.once) {
      const double length = cumulative_[i].back();
      if (st.dir < 0.0 && next_s <= 0.0) {  // turned back, and back where they came from
        st.s = 0.0;
        st.dir = 1.0;
        st.resting = kTryAgainAfter;
        continue;
      }
      next_s = std::clamp(next_s, 0.0, length);  // at the end: there
    }
    if (!robot_or_none) {
      st.s = next_s;
      drift_back(i, std::nullopt, dt, clearance);
      continue;
    }
    const Circle& robot = *robot_or_none;
    if (st.phase == Phase::kStandingAside) {
      standing_aside(i, robot, dt);
      continue;
    }
    const Vec2 now = centre(i);
    const Vec2 next = position(i, next_s) + st.aside;
    const double gap = p.radius + robot.radius;
    const double d_next = (next - robot.center).norm();
    const double d_now = (now - robot.center).norm();
    const Vec2 step = next - now, to_robot = robot.center - now;
    const bool toward = step.norm() > 1e-12 && to_robot.norm() > 1e-12 &&
                        step.dot(to_robot) > std::cos(70.0 * M_PI / 180.0) * step.norm() * to_robot.norm();
    // Wait when the step would bring the person closer than touching the robot, or, walking
    // toward it, closer than the personal space; once stepping around it, closer than passing it.
    const bool passing = (st.waiting >= st.patience || st.going_around) && st.aside.norm() > 0.0;
    const double keep = passing ? kPassMargin : p.personal_space;
    const bool touching = d_next < gap && d_next < d_now;
    if (touching || (keep > 0.0 && toward && d_next < gap + keep && d_next < d_now)) {
      blocked(i, step, robot, dt, clearance);
      continue;
    }
    st.s = next_s;
    if (!toward) {  // the robot is beside or behind: passed (or never in the way)
      st.waiting = 0.0;
      end_encounter(i);
    }
    drift_back(i, robot, dt, clearance);
  }
}

Encounter& People::begin_encounter(size_t i)
{
  auto& st = state_[i];
  const auto& p = people_[i];
  Encounter e;
  e.person = i;
  e.t = time_;
  // Nothing is drawn for people who only wait: their runs stay what they were.
  if (p.stand_aside_share > 0.0 || p.go_around_share > 0.0) {
    const double u = rng_.uniform();
    if (u < p.stand_aside_share) e.choice = EncounterChoice::kStandAside;
    else if (u < p.stand_aside_share + p.go_around_share) e.choice = EncounterChoice::kGoAround;
  }
  st.patience = p.patience;
  if (p.patience_max > p.patience) st.patience = p.patience + rng_.uniform() * (p.patience_max - p.patience);
  e.patience = st.patience;
  st.encounter = static_cast<int>(encounters_.size());
  encounters_.push_back(e);
  return encounters_.back();
}

void People::end_encounter(size_t i)
{
  state_[i].encounter = -1;
  state_[i].going_around = false;
}

void People::blocked(size_t i, const Vec2& walking, const Circle& robot, double dt, const StaticClearance& clearance)
{
  auto& st = state_[i];
  const auto& p = people_[i];
  Encounter& e = st.encounter >= 0 ? encounters_[static_cast<size_t>(st.encounter)] : begin_encounter(i);
  const Vec2 away = robot.center - centre(i);
  const bool making_way = away.norm() > 1e-9 && robot_velocity_.dot(away.normalized()) > kMakingWay;
  if (!making_way) st.waiting += dt;
  const double pass = p.radius + robot.radius + kPassMargin;
  if (e.choice == EncounterChoice::kStandAside && !e.no_room && walking.norm() > 1e-12) {
    const Vec2 dir = walking.normalized();
    if (const auto spot = stand_aside_spot(centre(i), dir, p.radius, robot, kRobotRoom, kMaxAside, clearance)) {
      st.phase = Phase::kStandingAside;
      st.walking = dir;
      st.aside_goal = st.aside + spot->side * spot->offset * Vec2(-dir.y(), dir.x());
      st.waiting = 0.0;
      e.stood_aside = true;
      return;
    }
    e.no_room = true;
  }
  if (e.choice == EncounterChoice::kGoAround && !e.no_room) {
    if (step_aside(i, walking, robot, pass, dt, clearance)) {
      st.going_around = true;
      e.went_around = true;
      return;
    }
    e.no_room = true;
  }
  if (st.waiting < st.patience) return;
  if (step_aside(i, walking, robot, pass, dt, clearance)) {
    e.went_around = true;
  } else if (p.turn_back) {
    // No way past: back the way they came (the fold of position() takes them back here later).
    st.dir = -st.dir;
    st.waiting = 0.0;
    e.turned_back = true;
    end_encounter(i);
  }
}

void People::standing_aside(size_t i, const Circle& robot, double dt)
{
  auto& st = state_[i];
  const auto& p = people_[i];
  st.waiting += dt;
  const Vec2 to_go = st.aside_goal - st.aside;
  const double limit = kSideSpeed * p.speed * dt;
  if (to_go.norm() > 1e-12) {
    const Vec2 move = to_go.norm() > limit ? Vec2(to_go.normalized() * limit) : to_go;
    // Not into the robot: the spot was chosen clear of the walls (stand_aside_spot).
    if ((centre(i) + move - robot.center).norm() >= p.radius + robot.radius) st.aside += move;
  }
  const Vec2 rel = robot.center - centre(i);
  const bool passed = rel.dot(st.walking) < -(p.radius + robot.radius) || rel.norm() > kRobotGone;
  if (passed || st.waiting >= st.patience) {
    // Back to walking (drift_back returns them to their path once the robot is clear).
    st.phase = Phase::kWalking;
    st.waiting = 0.0;
    end_encounter(i);
  }
}

std::optional<AsideSpot> People::stand_aside_spot(const Vec2& at, const Vec2& walking, double radius,
                                                  const Circle& robot, double robot_margin, double max_offset,
                                                  const StaticClearance& clearance)
{
  const Vec2 left(-walking.y(), walking.x());
  const double lateral = (robot.center - at).dot(left);
  const double first = lateral > 0.0 ? -1.0 : 1.0;  // away from the robot's side first
  const double need = radius + kWallMargin;
  const double robot_need = robot.radius + robot_margin;
  const double beside = radius + robot.radius + kAsidePass;  // person centre to the robot's, passing
  std::optional<AsideSpot> best;
  for (const double side : {first, -first}) {
    for (double o = 0.2; o <= max_offset + 1e-9; o += 0.05) {
      const Vec2 q = at + side * o * left;
      if (clearance(q, need + 0.1) < need) break;  // the wall on this side
      const Vec2 r = q - side * beside * left;     // where the robot passes them
      if (clearance(r, robot_need + 0.1) < robot_need) continue;
      if (!best || o < best->offset - 1e-9) best = AsideSpot{side, o};
      break;
    }
  }
  return best;
}

bool People::step_aside(size_t i, const Vec2& walking, const Circle& robot, double pass, double dt,
                        const StaticClearance& clearance)
{
  auto& st = state_[i];
  const auto& p = people_[i];
  if (walking.norm() < 1e-12) return false;
  const Vec2 now = centre(i);
  const Vec2 dir = walking.normalized(), left(-dir.y(), dir.x());
  const double lateral = (robot.center - now).dot(left);  // the robot's centre, sideways from the person
  const double need = p.radius + kWallMargin;
  auto room = [&](double offset) {
    for (const double f : {0.25, 0.5, 0.75, 1.0})
      if (clearance(now + f * offset * left, need + 0.1) < need) return false;
    return clearance(now + offset * left + 0.5 * dir, need + 0.1) >= need;  // and a little ahead
  };
  // Passing the robot to its right or to its left: the nearer side that has room.
  double best = std::numeric_limits<double>::infinity();
  for (const double offset : {lateral - pass, lateral + pass})
    if (std::fabs(offset) < std::fabs(best) && room(offset)) best = offset;
  if (!std::isfinite(best)) return false;
  const double limit = kSideSpeed * p.speed * dt;
  const Vec2 to = now + std::clamp(best, -limit, limit) * left;
  if ((to - robot.center).norm() < p.radius + robot.radius) return false;
  st.aside += to - now;
  return true;
}

void People::drift_back(size_t i, const std::optional<Circle>& robot, double dt, const StaticClearance& clearance)
{
  auto& st = state_[i];
  const auto& p = people_[i];
  const double off = st.aside.norm();
  if (off < 1e-12) return;
  const Vec2 aside = st.aside * (1.0 - std::min(off, kSideSpeed * p.speed * dt) / off);
  const Vec2 to = position(i, st.s) + aside;
  // Not back in front of the robot (that would be waiting again), nor nearer a wall than
  // people keep (unless the path itself runs that near: then no nearer than now).
  if (robot && (to - robot->center).norm() < p.radius + robot->radius + std::max(p.personal_space, kPassMargin) + 0.3)
    return;
  const double need = p.radius + kWallMargin;
  if (clearance(to, need + 0.1) < need && clearance(to, 1.0) < clearance(centre(i), 1.0)) return;
  st.aside = aside;
}

std::vector<Circle> People::discs() const
{
  std::vector<Circle> out;
  out.reserve(people_.size());
  for (size_t i = 0; i < people_.size(); ++i) out.push_back({centre(i), people_[i].radius});
  return out;
}

}  // namespace rgnav::sim
