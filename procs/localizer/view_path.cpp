#include "localizer/view_path.h"

#include <cmath>

namespace rgnav::localizer {

ViewPath::ViewPath(double spacing, double length, double turn_as_travel)
    : spacing_(spacing), length_(length), turn_as_travel_(turn_as_travel)
{
}

void ViewPath::add(const geometry::Pose2& odom_from_base, std::vector<Eigen::Vector2d> points)
{
  const auto travel_between = [&](const geometry::Pose2& a, const geometry::Pose2& b) {
    const geometry::Pose2 d = a.between(b);
    return d.translation().norm() + turn_as_travel_ * std::fabs(d.theta());
  };
  // The newest view stands in for the current scan until the robot has moved `spacing` past
  // the view before it; then it is kept and the current scan starts a new one.
  if (views_.size() >= 2 && travel_between(views_[views_.size() - 2].odom_from_base, odom_from_base) < spacing_) views_.pop_back();
  const double travel = views_.empty() ? 0.0 : views_.back().travel + travel_between(views_.back().odom_from_base, odom_from_base);
  views_.push_back({odom_from_base, std::move(points), travel});
  while (views_.size() > 1 && travel - views_.front().travel > length_) views_.pop_front();
}

std::vector<PlacedView> ViewPath::placed(const geometry::Pose2& odom_now) const
{
  std::vector<PlacedView> out;
  out.reserve(views_.size());
  for (const auto& v : views_) out.push_back({odom_now.between(v.odom_from_base), &v.points});
  return out;
}

}  // namespace rgnav::localizer
