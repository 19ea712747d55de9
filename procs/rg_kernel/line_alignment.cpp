#include "procs/rg_kernel/line_alignment.h"

#include <Eigen/Dense>

#include <cmath>

#include "procs/rg_kernel/line_map_fidelity.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

std::optional<geometry::Pose2> align_to_line_map(const std::vector<Vector2d>& points,
                                                 const std::vector<rgmap::LineSegment>& map, const LineAlignOptions& o)
{
  if (!o.enabled || map.empty() || static_cast<int>(points.size()) < o.min_matches) return std::nullopt;
  const SegmentIndex index(map, o.max_distance);
  geometry::Pose2 correction;   // identity
  // Residuals beyond this weigh less (Huber): clutter near a wall must not pull the scan.
  const double huber = 0.25 * o.max_distance;
  int matches = 0;
  for (int iter = 0; iter < o.iterations; ++iter) {
    std::vector<Vector2d> moved, normals;
    std::vector<double> residuals;
    for (const Vector2d& p : points) {
      const Vector2d q = correction * p;
      const int i = index.nearest(q);
      if (i < 0) continue;
      const auto& s = map[static_cast<size_t>(i)];
      const Vector2d d = s.b - s.a;
      if (d.norm() < 1e-9) continue;
      const Vector2d n = Vector2d(-d.y(), d.x()).normalized();
      moved.push_back(q);
      normals.push_back(n);
      residuals.push_back(n.dot(q - s.a));
    }
    matches = static_cast<int>(moved.size());
    if (matches < o.min_matches) return std::nullopt;
    // Rotation about the paired points' centroid keeps the three unknowns well scaled.
    Vector2d c = Vector2d::Zero();
    for (const auto& q : moved) c += q;
    c /= static_cast<double>(matches);
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (int k = 0; k < matches; ++k) {
      const Vector2d& n = normals[static_cast<size_t>(k)];
      const Vector2d r = moved[static_cast<size_t>(k)] - c;
      const Eigen::Vector3d j(n.x(), n.y(), n.x() * -r.y() + n.y() * r.x());
      const double e = residuals[static_cast<size_t>(k)];
      const double w = std::fabs(e) <= huber ? 1.0 : huber / std::fabs(e);
      h += w * j * j.transpose();
      g += w * j * e;
    }
    // Damping: a direction the walls do not constrain (along a hallway) stays where it is.
    h += 1e-3 * matches * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d step = -h.ldlt().solve(g);
    const geometry::Pose2 rot(0, 0, step.z());
    const Vector2d t = c + step.head<2>() - rot * c;
    correction = geometry::Pose2(t, step.z()) * correction;
    if (step.head<2>().norm() < 1e-5 && std::fabs(step.z()) < 1e-6) break;
  }
  // The shift where the scan's points are (the origin of the region frame may lie far away).
  Vector2d centre = Vector2d::Zero();
  for (const Vector2d& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  if ((correction * centre - centre).norm() > o.max_translation || std::fabs(correction.theta()) > o.max_rotation)
    return std::nullopt;
  return correction;
}

}  // namespace rgnav::rg_kernel
