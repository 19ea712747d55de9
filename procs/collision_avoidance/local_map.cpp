#include "collision_avoidance/local_map.h"

#include <cmath>
#include <limits>

namespace rgnav::collision_avoidance {

void LocalMap::add_scan(ScanPoints scan)
{
  scans_.push_back(std::move(scan));
  while (static_cast<int>(scans_.size()) > options_.max_scans) scans_.pop_front();
}

void LocalMap::set_grid_points(time::Time stamp, std::vector<Eigen::Vector2d> odom_points)
{
  grid_stamp_ = stamp;
  grid_points_ = std::move(odom_points);
}

void LocalMap::rebuild(time::Time now)
{
  while (!scans_.empty() && time::to_seconds(now - scans_.front().stamp) > options_.max_age) scans_.pop_front();
  if (!grid_points_.empty() && time::to_seconds(now - grid_stamp_) > options_.max_age) grid_points_.clear();
  points_.clear();
  for (const auto& s : scans_)
    for (const auto& p : s.points)
      if (p.squaredNorm() <= options_.max_range * options_.max_range) points_.push_back(s.odom_from_base * p);
  points_.insert(points_.end(), grid_points_.begin(), grid_points_.end());
  index_.clear();
  for (size_t i = 0; i < points_.size(); ++i) {
    const int ix = static_cast<int>(std::floor(points_[i].x() / options_.cell));
    const int iy = static_cast<int>(std::floor(points_[i].y() / options_.cell));
    index_[key(ix, iy)].push_back(static_cast<uint32_t>(i));
  }
}

double LocalMap::clearance(const Eigen::Vector2d& p, double radius) const
{
  double best2 = radius * radius;
  bool found = false;
  const int r = static_cast<int>(std::ceil(radius / options_.cell));
  const int cx = static_cast<int>(std::floor(p.x() / options_.cell));
  const int cy = static_cast<int>(std::floor(p.y() / options_.cell));
  for (int dx = -r; dx <= r; ++dx)
    for (int dy = -r; dy <= r; ++dy) {
      auto it = index_.find(key(cx + dx, cy + dy));
      if (it == index_.end()) continue;
      for (uint32_t i : it->second) {
        const double d2 = (points_[i] - p).squaredNorm();
        if (d2 <= best2) {
          best2 = d2;
          found = true;
        }
      }
    }
  return found ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
}

}  // namespace rgnav::collision_avoidance
