#include "procs/rg_kernel/laser_points.h"

#include <cmath>

namespace rgnav::rg_kernel {

std::vector<Eigen::Vector2d> laser_points(const sensors::LaserScan& s)
{
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(s.ranges.size());
  for (size_t i = 0; i < s.ranges.size(); ++i) {
    const double r = s.ranges[i];
    if (!(r > s.range_min && r < s.range_max)) continue;
    const double a = s.angle_min + static_cast<double>(i) * s.angle_increment;
    pts.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return pts;
}

}  // namespace rgnav::rg_kernel
