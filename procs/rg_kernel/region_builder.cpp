#include "procs/rg_kernel/region_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

bool segments_cross(const Vector2d& p, const Vector2d& q, const Vector2d& a, const Vector2d& b)
{
  auto cross = [](const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

void RegionBuilder::add_scan(StoredScan scan)
{
  auto it = scans_.find(scan.scan_id);
  if (it != scans_.end()) {
    if (scan.revision <= it->second.revision) return;  // old news (a duplicate or reordered message)
    it->second = std::move(scan);
    rebuild_lines();
    return;
  }
  std::vector<Vector2d> pts;
  pts.reserve(scan.laser_points.size());
  for (const auto& p : scan.laser_points) pts.push_back(scan.region_from_laser * p);
  auto fresh = extract_segments(pts, options_.extract);
  segments_.insert(segments_.end(), fresh.begin(), fresh.end());
  segments_ = merge_segments(std::move(segments_), options_.merge);
  scans_.emplace(scan.scan_id, std::move(scan));
}

void RegionBuilder::rebuild_lines()
{
  segments_.clear();
  for (const auto& [id, s] : scans_) {
    std::vector<Vector2d> pts;
    for (const auto& p : s.laser_points) pts.push_back(s.region_from_laser * p);
    auto fresh = extract_segments(pts, options_.extract);
    segments_.insert(segments_.end(), fresh.begin(), fresh.end());
    segments_ = merge_segments(std::move(segments_), options_.merge);
  }
}

int64_t RegionBuilder::raw_points() const
{
  int64_t n = 0;
  for (const auto& kv : scans_) n += static_cast<int64_t>(kv.second.laser_points.size());
  return n;
}

std::vector<Vector2d> RegionBuilder::laser_origins() const
{
  std::vector<std::pair<int64_t, Vector2d>> by_time;
  for (const auto& kv : scans_) by_time.push_back({kv.second.utime, kv.second.region_from_laser.translation()});
  std::sort(by_time.begin(), by_time.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Vector2d> out;
  for (const auto& e : by_time) out.push_back(e.second);
  return out;
}

void RegionBuilder::describe(rgmap::Region* region,
                             const std::vector<std::pair<Vector2d, Vector2d>>& gateway_lines) const
{
  region->segments = segments_;
  region->nscans = static_cast<int>(scans_.size());
  // In-region beams: origin and end point on the same side of every gateway line.
  struct Beam
  {
    Vector2d from, to;
  };
  std::vector<Beam> beams;
  Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Vector2d hi = -lo;
  for (const auto& [id, s] : scans_) {
    const Vector2d o = s.region_from_laser.translation();
    lo = lo.cwiseMin(o);
    hi = hi.cwiseMax(o);
    for (const auto& lp : s.laser_points) {
      const Vector2d p = s.region_from_laser * lp;
      bool crosses = false;
      for (const auto& g : gateway_lines) crosses = crosses || segments_cross(o, p, g.first, g.second);
      if (crosses || (p - o).norm() > options_.freespace_max_range) continue;
      beams.push_back({o, p});
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  if (beams.empty()) return;
  region->bbox_min = lo;
  region->bbox_max = hi;
  const double res = options_.freespace_resolution;
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / res)) + 1;
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y()) / res)) + 1;
  rgmap::FreespaceBitmap fs(res, geometry::Pose2(lo, 0.0), w, h);
  for (const auto& b : beams) fs.carve_ray(b.from, b.to, true);
  region->freespace = std::move(fs);
  // Completeness: observed (free) share of the bounding rectangle; accuracy: how tightly the
  // merged segments fit their points (1 at sigma 0, 0.5 at 2 cm).
  const double box = (hi.x() - lo.x()) * (hi.y() - lo.y());
  region->completeness = box > 0 ? std::min(1.0, region->freespace.free_cells() * res * res / box) : 0.0;
  double sum = 0, n = 0;
  for (const auto& s : segments_) {
    sum += s.sigma * s.support;
    n += s.support;
  }
  region->accuracy = n > 0 ? 1.0 / (1.0 + (sum / n) / 0.02) : 0.0;
}

}  // namespace rgnav::rg_kernel
