#include "scan_mapper/scan_normals.h"

#include <cmath>

#include "scan_mapper/point_map.h"

namespace rgnav::scan_mapper {
namespace {

// Sine of the angle between a step and the (unit) chord.
double bend(const Eigen::Vector2d& chord, const Eigen::Vector2d& step)
{
  return std::fabs(chord.x() * step.y() - chord.y() * step.x()) / step.norm();
}

}  // namespace

ScanNormals scan_normals(const Points& points, const Eigen::Vector2d& viewpoint, const ScanNormalOptions& o)
{
  const PointMap own(points, o.radius_m);
  ScanNormals out{own.normals(), own.has_normals()};
  if (o.beam_max_gap_m > 0.0) {
    const double max_bend = std::sin(o.beam_max_bend_rad);
    for (size_t i = 1; i + 1 < points.size(); ++i) {
      if (out.has_normal[i]) continue;
      const Eigen::Vector2d before = points[i] - points[i - 1], after = points[i + 1] - points[i];
      // Repeated points (points.min_spacing_m 0) give no direction.
      if (!(before.norm() > 0.0 && after.norm() > 0.0)) continue;
      if (before.norm() > o.beam_max_gap_m || after.norm() > o.beam_max_gap_m) continue;
      const Eigen::Vector2d chord = (points[i + 1] - points[i - 1]).normalized();
      if (bend(chord, before) > max_bend || bend(chord, after) > max_bend) continue;
      out.normals[i] = Eigen::Vector2d(-chord.y(), chord.x());
      out.has_normal[i] = 1;
    }
  }
  orient_normals_toward(points, viewpoint, &out.normals, out.has_normal);
  return out;
}

}  // namespace rgnav::scan_mapper
