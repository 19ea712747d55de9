// A polygonal test world and laser scans of it (the shared ray caster, wall_world.h), for
// registration and mapping tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "scan_mapper/scan_types.h"
#include "wall_world.h"

namespace rgnav::scan_mapper::testing {

using Segment = rgnav::testing::Wall;

// An L-shaped corridor system with rooms, pillars and a doorway: enough structure to
// constrain x, y and theta everywhere.
inline std::vector<Segment> office_world()
{
  using rgnav::testing::add;
  using rgnav::testing::box;
  std::vector<Segment> w;
  add(&w, box(-2, -2, 12, 10));        // outer walls
  w.push_back({{3, -2}, {3, 4}});      // inner walls with gaps (doorways)
  w.push_back({{3, 5}, {3, 10}});
  w.push_back({{3, 6}, {8, 6}});
  w.push_back({{9, 6}, {12, 6}});
  add(&w, box(6, 1, 7, 2));            // pillars and furniture
  add(&w, box(0, 7, 0.6, 7.6));
  add(&w, box(9.5, 8, 10.5, 8.5));
  w.push_back({{-2, 3}, {0, 3.5}});    // a slanted wall
  return w;
}

struct LaserModel
{
  int beams = 181;
  double fov = M_PI;
  double max_range = 30.0;
  double noise_m = 0.0;
  double outlier_share = 0.0;  // beams replaced by a random short range
};

inline sensors::LaserScan cast_scan(const std::vector<Segment>& world, const Pose2& map_from_laser,
                                    const LaserModel& m, std::mt19937* rng = nullptr, int64_t id = 1,
                                    int64_t utime = 0)
{
  sensors::LaserScan s;
  s.scan_id = id;
  s.utime = utime;
  s.angle_min = static_cast<float>(-m.fov / 2);
  s.angle_increment = static_cast<float>(m.fov / (m.beams - 1));
  s.range_min = 0.05f;
  s.range_max = static_cast<float>(m.max_range);
  std::normal_distribution<double> noise(0.0, m.noise_m);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < m.beams; ++i) {
    const double a = map_from_laser.theta() + s.angle_min + i * static_cast<double>(s.angle_increment);
    const Eigen::Vector2d o(map_from_laser.x(), map_from_laser.y()), d(std::cos(a), std::sin(a));
    const double best = std::min(m.max_range, rgnav::testing::nearest_wall(world, o, d));
    double r = best;
    if (rng && best < m.max_range) r += noise(*rng);
    if (rng && m.outlier_share > 0 && uni(*rng) < m.outlier_share) r = 0.3 + uni(*rng) * 3.0;
    s.ranges.push_back(static_cast<float>(r));
  }
  return s;
}

}  // namespace rgnav::scan_mapper::testing
