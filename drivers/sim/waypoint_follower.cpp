#include "sim/waypoint_follower.h"

#include <algorithm>
#include <cmath>

namespace rgnav::sim {

std::optional<DriveCommand> WaypointFollower::command_at(int64_t)
{
  const Pose2 p = pose_();
  while (next_ < waypoints_.size() && (waypoints_[next_] - Vec2(p.x, p.y)).norm() < options_.reach) ++next_;
  if (done()) return DriveCommand{};
  const Vec2 to = waypoints_[next_] - Vec2(p.x, p.y);
  const double err = normalize_angle(std::atan2(to.y(), to.x()) - p.theta);
  DriveCommand cmd;
  // Proportional turn, saturated; drive only when aligned, slowing down on the last metre.
  cmd.omega = std::clamp(3.0 * err, -options_.omega, options_.omega);
  if (std::fabs(err) < options_.aligned) cmd.v = std::min(options_.v, 0.3 + to.norm());
  return cmd;
}

}  // namespace rgnav::sim
