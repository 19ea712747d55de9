#include "procs/tour_runner/pure_pursuit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::tour_runner {

Command pursue(const PursuitOptions& o, const geometry::Pose2& odom_from_base, const Eigen::Vector2d& odom_target,
               const std::vector<Eigen::Vector2d>& obstacles_in_base)
{
  Command c;
  const Eigen::Vector2d t = odom_from_base.inverse() * odom_target;  // target in the base frame
  const double heading_error = std::atan2(t.y(), t.x());
  const double dist = t.norm();

  // Free distance straight ahead within the robot's width.
  double free_ahead = std::numeric_limits<double>::infinity();
  for (const auto& p : obstacles_in_base)
    if (p.x() > 0 && std::fabs(p.y()) < o.robot_radius + 0.05) free_ahead = std::min(free_ahead, p.x() - o.robot_radius);

  c.omega = std::clamp(2.0 * heading_error, -o.max_omega, o.max_omega);
  if (std::fabs(heading_error) > o.turn_in_place_angle) return c;  // rotate first

  // Pure pursuit: curvature 2 y / L^2 toward the target, speed limited by turn and clearance.
  double v = std::min(o.max_v, 0.8 * dist + 0.1);
  v *= std::max(0.2, std::cos(heading_error));
  if (free_ahead < o.slow_distance)
    v *= std::clamp((free_ahead - o.stop_distance) / (o.slow_distance - o.stop_distance), 0.0, 1.0);
  if (free_ahead <= o.stop_distance) {
    c.blocked = true;
    v = 0;
  }
  c.v = v;
  if (dist > 1e-6) c.omega = std::clamp(v * 2.0 * t.y() / (dist * dist) + 0.5 * heading_error, -o.max_omega, o.max_omega);
  return c;
}

}  // namespace rgnav::tour_runner
