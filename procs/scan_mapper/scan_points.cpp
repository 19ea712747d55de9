#include "scan_mapper/scan_points.h"

#include <algorithm>
#include <cmath>

namespace rgnav::scan_mapper {

Points scan_to_points(const sensors::LaserScan& scan, const Pose2& base_from_laser, const PointFilterOptions& o)
{
  Points raw;
  raw.reserve(scan.ranges.size());
  const double lo = std::max<double>(o.min_range_m, scan.range_min);
  const double hi = std::min<double>(o.max_range_m, scan.range_max);
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    const double r = scan.ranges[i];
    if (!(r >= lo) || !(r < hi)) continue;
    const double a = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    raw.push_back(base_from_laser * Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
  }
  return thin_points(raw, o.min_spacing_m);
}

Points thin_points(const Points& points, double spacing)
{
  Points out;
  out.reserve(points.size());
  const double s2 = spacing * spacing;
  for (const auto& p : points)
    if (out.empty() || (p - out.back()).squaredNorm() >= s2) out.push_back(p);
  return out;
}

Points transform_points(const Pose2& a_from_b, const Points& points_in_b)
{
  Points out;
  out.reserve(points_in_b.size());
  const double c = std::cos(a_from_b.theta()), s = std::sin(a_from_b.theta());
  for (const auto& p : points_in_b)
    out.emplace_back(a_from_b.x() + c * p.x() - s * p.y(), a_from_b.y() + s * p.x() + c * p.y());
  return out;
}

}  // namespace rgnav::scan_mapper
