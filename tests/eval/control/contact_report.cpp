#include "contact_report.h"

#include <algorithm>
#include <cmath>

namespace rgnav::bench {

void ContactHistory::add(double t, const Eigen::Vector2d& robot, const std::vector<Eigen::Vector2d>& people)
{
  samples_.push_back({t, robot, people});
  while (!samples_.empty() && t - samples_.front().t > keep_s_) samples_.pop_front();
}

std::optional<ContactSplit> ContactHistory::split(size_t person, double window, double radii) const
{
  if (samples_.empty() || person >= samples_.back().people.size()) return std::nullopt;
  const double t_end = samples_.back().t;
  size_t first = samples_.size() - 1;
  while (first > 0 && t_end - samples_[first - 1].t <= window + 1e-9) --first;
  ContactSplit s;
  s.window_s = t_end - samples_[first].t;
  s.gap_before_m = (samples_[first].people[person] - samples_[first].robot).norm() - radii;
  // Step by step, each displacement projected on the line between the two at the step's
  // start: the two parts add up to the change of the distance (to first order).
  for (size_t k = first; k + 1 < samples_.size(); ++k) {
    const auto& a = samples_[k];
    const auto& b = samples_[k + 1];
    const Eigen::Vector2d d = a.people[person] - a.robot;
    if (d.norm() < 1e-9) continue;
    const Eigen::Vector2d u = d / d.norm();  // robot -> person
    s.robot_closing_m += (b.robot - a.robot).dot(u);
    s.person_closing_m -= (b.people[person] - a.people[person]).dot(u);
  }
  size_t recent = samples_.size() - 1;
  while (recent > 0 && t_end - samples_[recent - 1].t <= 0.5 + 1e-9) --recent;
  if (t_end - samples_[recent].t > 1e-9)
    s.person_speed_mps = (samples_.back().people[person] - samples_[recent].people[person]).norm() / (t_end - samples_[recent].t);
  const double r = std::max(0.0, s.robot_closing_m), p = std::max(0.0, s.person_closing_m);
  if (r < 0.02 && p < 0.02) s.closed_by = "neither";
  else if (r > 2.0 * p) s.closed_by = "robot";
  else if (p > 2.0 * r) s.closed_by = "person";
  else s.closed_by = "both";
  return s;
}

}  // namespace rgnav::bench
