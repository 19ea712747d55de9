#include "sim/people.h"

#include <cmath>

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

void People::advance(double dt, const std::optional<Circle>& robot_or_none)
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
      continue;
    }
    const Circle& robot = *robot_or_none;
    const Vec2 next = position(i, next_s);
    const Vec2 now = position(i, st.s);
    const double gap = p.radius + robot.radius;
    // Wait when the step would bring the person closer than touching the robot, or, walking
    // toward it, closer than the personal space.
    const double d_next = (next - robot.center).norm();
    const double d_now = (now - robot.center).norm();
    if (d_next < gap && d_next < d_now) continue;
    const Vec2 step = next - now, to_robot = robot.center - now;
    const bool toward = step.norm() > 1e-12 && to_robot.norm() > 1e-12 &&
                        step.dot(to_robot) > std::cos(70.0 * M_PI / 180.0) * step.norm() * to_robot.norm();
    if (p.personal_space > 0.0 && toward && d_next < gap + p.personal_space && d_next < d_now) continue;
    st.s = next_s;
  }
}

std::vector<Circle> People::discs() const
{
  std::vector<Circle> out;
  out.reserve(people_.size());
  for (size_t i = 0; i < people_.size(); ++i) out.push_back({position(i, state_[i].s), people_[i].radius});
  return out;
}

}  // namespace rgnav::sim
