#include "procs/tour_runner/pure_pursuit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::tour_runner {

namespace {

// How far the circular robot can drive along `heading` (base frame) before it touches one of
// the points, with `margin` added to its radius.
double free_distance(const std::vector<Eigen::Vector2d>& obstacles, double heading, double radius)
{
  const double c = std::cos(heading), s = std::sin(heading);
  double free = std::numeric_limits<double>::infinity();
  for (const auto& p : obstacles) {
    const double along = c * p.x() + s * p.y();
    const double across = -s * p.x() + c * p.y();
    if (along <= 0 || std::fabs(across) >= radius) continue;
    free = std::min(free, along - std::sqrt(radius * radius - across * across));
  }
  return free;
}

}  // namespace

Command pursue(const PursuitOptions& o, const geometry::Pose2& odom_from_base, const Eigen::Vector2d& odom_target,
               const std::vector<Eigen::Vector2d>& obstacles_in_base)
{
  Command c;
  const Eigen::Vector2d t = odom_from_base.inverse() * odom_target;  // target in the base frame
  const double heading_error = std::atan2(t.y(), t.x());
  const double dist = t.norm();
  const double radius = o.robot_radius + 0.05;
  const double free_ahead = free_distance(obstacles_in_base, 0.0, radius);

  c.omega = std::clamp(2.0 * heading_error, -o.max_omega, o.max_omega);
  if (std::fabs(heading_error) > o.turn_in_place_angle) return c;  // rotate first

  if (free_ahead <= o.stop_distance) {
    // Blocked ahead: turn in place toward the free heading closest to the target's direction
    // (the freespace orientation idea of Holz et al. 5.1), then drive on.
    c.blocked = true;
    double best = 0, best_cost = std::numeric_limits<double>::infinity();
    for (int k = -9; k <= 9; ++k) {
      const double h = k * M_PI / 18;
      if (free_distance(obstacles_in_base, h, radius) < o.slow_distance) continue;
      const double cost = std::fabs(geometry::normalize_angle(h - heading_error));
      if (cost < best_cost) {
        best_cost = cost;
        best = h;
      }
    }
    c.omega = std::isfinite(best_cost) ? std::clamp(1.5 * best, -o.max_omega, o.max_omega) : 0.0;
    if (std::isfinite(best_cost)) c.escape_heading = best;
    return c;
  }

  // Pure pursuit: curvature 2 y / L^2 toward the target, speed limited by turn and clearance.
  double v = std::min(o.max_v, 0.8 * dist + 0.1);
  v *= std::max(0.2, std::cos(heading_error));
  if (free_ahead < o.slow_distance)
    v *= std::clamp((free_ahead - o.stop_distance) / (o.slow_distance - o.stop_distance), 0.1, 1.0);
  c.v = v;
  if (dist > 1e-6) c.omega = std::clamp(v * 2.0 * t.y() / (dist * dist) + 0.5 * heading_error, -o.max_omega, o.max_omega);
  return c;
}

Command escape(const PursuitOptions& o, double heading_error, const std::vector<Eigen::Vector2d>& obstacles_in_base)
{
  Command c;
  if (std::fabs(heading_error) > 0.15) {
    c.omega = std::clamp(1.5 * heading_error, -o.max_omega, o.max_omega);
    return c;
  }
  const double free_ahead = free_distance(obstacles_in_base, 0.0, o.robot_radius + 0.05);
  if (free_ahead <= o.stop_distance) {
    c.blocked = true;
    return c;
  }
  c.v = std::min(0.2, o.max_v);
  c.omega = std::clamp(1.5 * heading_error, -o.max_omega, o.max_omega);
  return c;
}

}  // namespace rgnav::tour_runner
