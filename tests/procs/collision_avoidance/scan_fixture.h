// Test-only: synthetic laser readings of segment obstacles (a tiny ray caster).
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "collision_avoidance/reactive.h"
#include "geometry/pose2.h"

namespace rgnav::collision_avoidance::testing {

struct Wall
{
  Eigen::Vector2d a, b;
};

// 181 beams over 180 deg from the laser pose (odom frame); no return = range_max.
inline std::vector<PolarReading> cast(const geometry::Pose2& laser, const std::vector<Wall>& walls,
                                      double range_max = 8.0)
{
  std::vector<PolarReading> out;
  for (int i = 0; i < 181; ++i) {
    const double bearing = -M_PI_2 + i * M_PI / 180.0;
    const double th = laser.theta() + bearing;
    const Eigen::Vector2d o = laser.translation(), d(std::cos(th), std::sin(th));
    double best = range_max;
    for (const auto& w : walls) {
      const Eigen::Vector2d e = w.b - w.a;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::fabs(den) < 1e-12) continue;
      const Eigen::Vector2d r = w.a - o;
      const double t = (r.x() * e.y() - r.y() * e.x()) / den;
      const double u = (r.x() * d.y() - r.y() * d.x()) / den;
      if (t > 0 && u >= 0 && u <= 1) best = std::min(best, t);
    }
    out.push_back({bearing, best});
  }
  return out;
}

// The four sides of an axis-aligned box.
inline std::vector<Wall> box(double x0, double y0, double x1, double y1)
{
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

}  // namespace rgnav::collision_avoidance::testing
