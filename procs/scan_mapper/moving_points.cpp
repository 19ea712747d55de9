#include "scan_mapper/moving_points.h"

#include <cmath>

namespace rgnav::scan_mapper {

ScanView::ScanView(const sensors::LaserScan& scan, const Pose2& map_from_laser, const MovingPointOptions& o)
    : scan_(scan),
      laser_from_map_(map_from_laser.inverse()),
      origin_(map_from_laser.translation()),
      margin_(o.margin_m),
      min_cos_incidence_(std::cos(o.max_incidence_deg * M_PI / 180.0))
{
}

bool ScanView::sees_through(const Eigen::Vector2d& p, const Eigen::Vector2d& normal) const
{
  const Eigen::Vector2d q = laser_from_map_ * p;
  const double d = q.norm();
  if (d < 1e-6 || scan_.ranges.size() < 2 || !(scan_.angle_increment > 0.f)) return false;
  if (normal.squaredNorm() > 0.0) {
    // Incidence of this scan's beam on the point's surface (either face).
    const double cos_incidence = std::fabs(normal.dot((p - origin_) / d));
    if (cos_incidence < min_cos_incidence_) return false;
  }
  const double f = (std::atan2(q.y(), q.x()) - scan_.angle_min) / scan_.angle_increment;
  if (!(f >= 0.0)) return false;
  const auto i0 = static_cast<size_t>(std::floor(f));
  if (i0 + 1 >= scan_.ranges.size()) return false;
  for (size_t i = i0; i <= i0 + 1; ++i) {
    const double r = scan_.ranges[i];
    // No return (at or beyond the limit): nothing within the range limit.
    const double reach = (r >= scan_.range_max) ? static_cast<double>(scan_.range_max) : r;
    if (!(r > scan_.range_min) || !(reach > d + margin_)) return false;
  }
  return true;
}

void mark_seen_through(const std::vector<ScanView>& views, const Points& points, const Points& normals,
                       const std::vector<char>& has_normal, std::vector<char>* keep)
{
  keep->resize(points.size(), 1);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!(*keep)[i]) continue;
    const Eigen::Vector2d n = (i < has_normal.size() && has_normal[i]) ? normals[i] : Eigen::Vector2d::Zero();
    for (const auto& v : views)
      if (v.sees_through(points[i], n)) {
        (*keep)[i] = 0;
        break;
      }
  }
}

}  // namespace rgnav::scan_mapper
