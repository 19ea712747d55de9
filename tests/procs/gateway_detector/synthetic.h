// Analytic test scenes for the gateway detector: scans from the shared ray caster (wall_world.h)
// and hallway crossings of every class (the approach hallway runs along +x, the crossing square
// is [0, w] x [-w/2, w/2]).
#pragma once

#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "gateway_detector/measures.h"
#include "gateway_detector/scan.h"
#include "wall_world.h"

namespace rgnav::gateway_detector::test {

using rgnav::testing::Wall;
using rgnav::testing::Walls;

inline sensors::LaserScan cast(const Walls& walls, const geometry::Pose2& world_from_laser, double noise = 0.0, unsigned seed = 1,
                 int beams = 181, double range_max = 8.183)
{
  sensors::LaserScan s;
  s.angle_min = -M_PI / 2;
  s.angle_increment = M_PI / (beams - 1);
  s.range_max = static_cast<float>(range_max);  // as laser_scan_t carries it: max-range readings are "no return"
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  const Vec2 o = world_from_laser.translation();
  for (int i = 0; i < beams; ++i) {
    const double a = world_from_laser.theta() + s.bearing(static_cast<size_t>(i));
    const Vec2 d(std::cos(a), std::sin(a));
    const double best = rgnav::testing::nearest_wall(walls, o, d, 1e-9);
    double r = best + (noise > 0 ? n(rng) : 0.0);
    s.ranges.push_back(static_cast<float>(best < range_max ? std::max(0.01, r) : range_max));
  }
  return s;
}

// A crossing of class c (CrossingClass) with hallway width w; branches are `branch` long and
// closed at their ends.
inline Walls crossing(int c, double w, double approach = 10.0, double branch = 5.0)
{
  const double h = w / 2;
  const bool left = expects_open(c, kLeftSector), front = expects_open(c, kFrontSector),
             right = expects_open(c, kRightSector);
  Walls ws;
  ws.push_back({{-approach, h}, {0, h}});
  ws.push_back({{-approach, -h}, {0, -h}});
  if (left) {
    ws.push_back({{0, h}, {0, h + branch}});
    ws.push_back({{w, h}, {w, h + branch}});
    ws.push_back({{0, h + branch}, {w, h + branch}});
  } else {
    ws.push_back({{0, h}, {w, h}});
  }
  if (right) {
    ws.push_back({{0, -h}, {0, -h - branch}});
    ws.push_back({{w, -h}, {w, -h - branch}});
    ws.push_back({{0, -h - branch}, {w, -h - branch}});
  } else {
    ws.push_back({{0, -h}, {w, -h}});
  }
  if (front) {
    ws.push_back({{w, h}, {w + branch, h}});
    ws.push_back({{w, -h}, {w + branch, -h}});
    ws.push_back({{w + branch, -h}, {w + branch, h}});
  } else {
    ws.push_back({{w, -h}, {w, h}});
  }
  return ws;
}

// A hallway wall at x = wall_x across y in [-4, 4] with a door gap of `width` centred at y = 0
// and a room behind it (depth `room`).
inline Walls door(double wall_x, double width, double room = 4.0)
{
  const double h = width / 2;
  return {{{wall_x, h}, {wall_x, 4.0}},
          {{wall_x, -4.0}, {wall_x, -h}},
          {{wall_x + room, -4.0}, {wall_x + room, 4.0}},
          {{wall_x, 4.0}, {wall_x + room, 4.0}},
          {{wall_x, -4.0}, {wall_x + room, -4.0}},
          {{-3.0, 1.5}, {wall_x, 1.5}},
          {{-3.0, -1.5}, {wall_x, -1.5}}};
}

}  // namespace rgnav::gateway_detector::test
