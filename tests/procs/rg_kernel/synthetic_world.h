// Worlds for RG kernel tests (two rooms joined by a door, hallways, furniture, pillars) and
// laser end points cast in them with the shared ray caster (wall_world.h).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/pose2.h"
#include "wall_world.h"

namespace rgnav::rg_kernel::testing {

using rgnav::testing::box;
using rgnav::testing::Wall;

// Room A [0,4]x[0,3], room B [4,8]x[0,3], door in x = 4 between y = 1 and y = 2.
inline std::vector<Wall> two_rooms()
{
  using V = Eigen::Vector2d;
  return {{V(0, 0), V(8, 0)}, {V(0, 3), V(8, 3)}, {V(0, 0), V(0, 3)}, {V(8, 0), V(8, 3)},
          {V(4, 0), V(4, 1)}, {V(4, 2), V(4, 3)}};
}

// A straight hallway y in [0, 2] from x = 0 to 12 with an X-crossing at x in [4, 6] (branches
// north to y = 6 and south to y = -4).
inline std::vector<Wall> hallway_with_crossing()
{
  using V = Eigen::Vector2d;
  return {{V(0, 0), V(4, 0)},   {V(6, 0), V(12, 0)},  {V(0, 2), V(4, 2)},  {V(6, 2), V(12, 2)},
          {V(0, 0), V(0, 2)},   {V(12, 0), V(12, 2)}, {V(4, 2), V(4, 6)},  {V(6, 2), V(6, 6)},
          {V(4, 6), V(6, 6)},   {V(4, 0), V(4, -4)},  {V(6, 0), V(6, -4)}, {V(4, -4), V(6, -4)}};
}

// A 2 m hallway y in [0, 2] along x in [0, 14]; a 3 m wide, 4 m deep bay south of it, open onto
// it over its whole width (x in [5, 8]).
inline std::vector<Wall> hallway_with_bay()
{
  using V = Eigen::Vector2d;
  return {{V(0, 0), V(0, 2)}, {V(14, 0), V(14, 2)}, {V(0, 2), V(14, 2)}, {V(0, 0), V(5, 0)},
          {V(8, 0), V(14, 0)}, {V(5, 0), V(5, -4)}, {V(8, 0), V(8, -4)}, {V(5, -4), V(8, -4)}};
}

// A round pillar.
struct Pillar
{
  Eigen::Vector2d c;
  double r;
};

// 181 beams over 180 degrees, end points in the laser frame (= base frame here).
inline std::vector<Eigen::Vector2d> cast(const std::vector<Wall>& walls, const geometry::Pose2& pose, double max_range = 8.0,
                                         const std::vector<Pillar>& pillars = {})
{
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 181; ++i) {
    const double a = -M_PI / 2 + i * M_PI / 180;
    const Eigen::Vector2d o = pose.translation();
    const Eigen::Vector2d d(std::cos(pose.theta() + a), std::sin(pose.theta() + a));
    double best = rgnav::testing::nearest_wall(walls, o, d);
    for (const auto& p : pillars) {
      // |o + t d - c| = r, nearest t > 0.
      const Eigen::Vector2d f = o - p.c;
      const double b = f.dot(d), disc = b * b - (f.squaredNorm() - p.r * p.r);
      if (disc < 0) continue;
      const double t = -b - std::sqrt(disc);
      if (t > 0) best = std::min(best, t);
    }
    if (best < max_range) pts.emplace_back(best * std::cos(a), best * std::sin(a));
  }
  return pts;
}

}  // namespace rgnav::rg_kernel::testing
