#include "sim/people.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::sim {

People::People(std::vector<Person> people) : people_(std::move(people)), state_(people_.size())
{
  for (const auto& p : people_) {
    std::vector<double> cum{0.0};
    for (size_t k = 1; k < p.path.size(); ++k) cum.push_back(cum.back() + (p.path[k] - p.path[k - 1]).norm());
    if (p.loop && p.path.size() > 1) cum.push_back(cum.back() + (p.path.front() - p.path.back()).norm());
    cumulative_.push_back(std::move(cum));
  }
}

Vec2 People::position(size_t i, double s) const
{
  const auto& p = people_[i];
  const auto& cum = cumulative_[i];
  const double length = cum.back();
  if (p.path.size() < 2 || length <= 0.0) return p.path.front();
  // Loop: wrap around. Back and forth: fold the walk onto [0, length].
  if (p.loop) {
    s = std::fmod(s, length);
  } else {
    s = std::fmod(s, 2.0 * length);
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
}  // namespace

void People::advance(double dt, const std::optional<Circle>& robot_or_none, const StaticClearance& clearance)
{
  for (size_t i = 0; i < people_.size(); ++i) {
    auto& st = state_[i];
    const auto& p = people_[i];
    if (st.waited < p.start_delay) {
      st.waited += dt;
      continue;
    }
    const double next_s = st.s + p.speed * dt;
    if (!robot_or_none) {
      st.s = next_s;
      drift_back(i, std::nullopt, dt, clearance);
      continue;
    }
    const Circle& robot = *robot_or_none;
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
    const bool passing = st.waiting >= p.patience && st.aside.norm() > 0.0;
    const double keep = passing ? kPassMargin : p.personal_space;
    const bool touching = d_next < gap && d_next < d_now;
    if (touching || (keep > 0.0 && toward && d_next < gap + keep && d_next < d_now)) {
      st.waiting += dt;
      if (st.waiting >= p.patience) step_aside(i, step, robot, gap + kPassMargin, dt, clearance);
      continue;
    }
    st.s = next_s;
    if (!toward) st.waiting = 0.0;  // the robot is beside or behind: passed (or never in the way)
    drift_back(i, robot, dt, clearance);
  }
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
