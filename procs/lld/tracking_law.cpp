#include "lld/tracking_law.h"

#include <cmath>

namespace rgnav::lld {

TrackingError tracking_error(const geometry::Pose2& reference, const geometry::Pose2& robot)
{
  const double c = std::cos(robot.theta()), s = std::sin(robot.theta());
  const double dx = reference.x() - robot.x(), dy = reference.y() - robot.y();
  TrackingError e;
  e.e_x = c * dx + s * dy;
  e.e_y = -s * dx + c * dy;
  e.e_theta = geometry::normalize_angle(reference.theta() - robot.theta());
  return e;
}

VelocityCommand kanayama(const TrackingError& e, double v_r, double omega_r, const TrackingGains& g)
{
  VelocityCommand u;
  u.v = v_r * std::cos(e.e_theta) + g.k_x * e.e_x;
  u.omega = omega_r + v_r * (g.k_y * e.e_y + g.k_theta * std::sin(e.e_theta));
  return u;
}

double lyapunov(const TrackingError& e, const TrackingGains& g)
{
  return 0.5 * (e.e_x * e.e_x + e.e_y * e.e_y) + (1.0 - std::cos(e.e_theta)) / g.k_y;
}

}  // namespace rgnav::lld
