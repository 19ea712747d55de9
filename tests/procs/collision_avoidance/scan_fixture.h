// Test-only: synthetic laser readings of segment obstacles (the shared ray caster, wall_world.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "collision_avoidance/local_map.h"
#include "collision_avoidance/reactive.h"
#include "geometry/pose2.h"
#include "wall_world.h"

namespace rgnav::collision_avoidance::testing {

using rgnav::testing::box;
using rgnav::testing::Wall;

// 181 beams over 180 deg from the laser pose (odom frame); no return = range_max.
inline std::vector<PolarReading> cast(const geometry::Pose2& laser, const std::vector<Wall>& walls,
                                      double range_max = 8.0)
{
  std::vector<PolarReading> out;
  for (int i = 0; i < 181; ++i) {
    const double bearing = -M_PI_2 + i * M_PI / 180.0;
    const double th = laser.theta() + bearing;
    const Eigen::Vector2d o = laser.translation(), d(std::cos(th), std::sin(th));
    out.push_back({bearing, std::min(range_max, rgnav::testing::nearest_wall(walls, o, d))});
  }
  return out;
}

// The same scan as the local map takes it, taken at `laser` at `stamp`: the hits as points, every
// beam (cut at max_range) in the outline of the free space.
inline ScanPoints scan_points(const geometry::Pose2& laser, const std::vector<Wall>& walls, time::Time stamp,
                              double max_range)
{
  ScanPoints s;
  s.stamp = stamp;
  s.odom_from_base = laser;
  for (const auto& r : cast(laser, walls)) {
    const Eigen::Vector2d p(r.range * std::cos(r.bearing), r.range * std::sin(r.bearing));
    if (r.range < 8.0) s.points.push_back(p);
    s.outline.push_back(p * (std::min(r.range, max_range) / r.range));
  }
  return s;
}

}  // namespace rgnav::collision_avoidance::testing
