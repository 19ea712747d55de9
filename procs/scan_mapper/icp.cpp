#include "scan_mapper/icp.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "geometry/symmetric_eigen2.h"

namespace rgnav::scan_mapper {
namespace {

struct Normal
{
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double sq = 0.0;
  int n = 0;
  double line_sq = 0.0;  // of the point-to-line residuals alone
  int line_n = 0;

  void add(const Eigen::Vector3d& J, double r, double w)
  {
    H += w * J * J.transpose();
    g += w * J * r;
    sq += r * r;
    ++n;
  }
};

// The scan with its oriented normals, if any, and the pairing rule.
struct ScanSide
{
  const Points& points;
  const Points* normals = nullptr;          // null: no normal check
  const std::vector<char>* has_normal = nullptr;
  double min_cos = -1.0;

  // Nearest model point within max_dist that may be the same surface as scan point i, placed
  // at p by the pose with rotation (c, s).
  int pair(const PointMap& model, size_t i, const Eigen::Vector2d& p, double c, double s, double max_dist) const
  {
    if (!normals || !(*has_normal)[i]) return model.nearest(p, max_dist);
    const Eigen::Vector2d& n = (*normals)[i];
    return model.nearest(p, max_dist, Eigen::Vector2d(c * n.x() - s * n.y(), s * n.x() + c * n.y()), min_cos);
  }
};

// Accumulates the Gauss-Newton system for the correspondences within max_dist.
Normal linearize(const ScanSide& scan, const PointMap& model, const Pose2& T, double max_dist)
{
  Normal ne;
  const double c = std::cos(T.theta()), s = std::sin(T.theta());
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const auto& q = scan.points[i];
    const Eigen::Vector2d p(T.x() + c * q.x() - s * q.y(), T.y() + s * q.x() + c * q.y());
    const int j = scan.pair(model, i, p, c, s, max_dist);
    if (j < 0) continue;
    const Eigen::Vector2d d = p - model.points()[static_cast<size_t>(j)];
    const Eigen::Vector2d dp_dth(-s * q.x() - c * q.y(), c * q.x() - s * q.y());
    // Huber weight on the residual, scale tied to the current threshold.
    const double k = 0.5 * max_dist;
    if (model.has_normal(j)) {
      const Eigen::Vector2d& n = model.normal(j);
      const double r = n.dot(d);
      const double w = std::fabs(r) <= k ? 1.0 : k / std::fabs(r);
      ne.add(Eigen::Vector3d(n.x(), n.y(), n.dot(dp_dth)), r, w);
      ne.line_sq += r * r;
      ++ne.line_n;
    } else {
      const double w = d.norm() <= k ? 1.0 : k / d.norm();
      ne.add(Eigen::Vector3d(1.0, 0.0, dp_dth.x()), d.x(), w);
      ne.add(Eigen::Vector3d(0.0, 1.0, dp_dth.y()), d.y(), w);
      --ne.n;
    }
  }
  return ne;
}

IcpResult register_scan(const ScanSide& scan, const PointMap& model, const Pose2& guess, const IcpOptions& o)
{
  IcpResult res;
  res.map_from_scan = guess;
  if (scan.points.size() < 5 || model.size() < 5) return res;
  Pose2 T = guess;
  double max_dist = o.initial_max_distance_m;
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    const Normal ne = linearize(scan, model, T, max_dist);
    if (ne.n < 5) break;
    // Small Levenberg damping keeps degenerate directions (a corridor) where the guess put them.
    Eigen::Matrix3d H = ne.H;
    H.diagonal() += Eigen::Vector3d(1e-6, 1e-6, 1e-6) * std::max(1.0, H.trace());
    Eigen::Vector3d delta = -H.ldlt().solve(ne.g);
    if (!o.estimate_rotation) {
      delta.head<2>() = -H.topLeftCorner<2, 2>().ldlt().solve(ne.g.head<2>());
      delta.z() = 0.0;
    }
    if (!delta.allFinite()) break;
    T = Pose2{T.x() + delta.x(), T.y() + delta.y(), normalize_angle(T.theta() + delta.z())};
    const bool small = std::hypot(delta.x(), delta.y()) < o.converged_translation_m &&
                       std::fabs(delta.z()) < o.converged_rotation_rad;
    const bool at_floor = max_dist <= o.final_max_distance_m;
    if (small && at_floor) {
      ++it;
      break;
    }
    max_dist = std::max(o.final_max_distance_m, max_dist * o.decay);
  }
  res.iterations = it;
  res.map_from_scan = T;

  const Normal fin = linearize(scan, model, T, o.final_max_distance_m);
  res.correspondences = fin.n;
  res.rms_m = fin.n > 0 ? std::sqrt(fin.sq / fin.n) : 0.0;
  res.surface_rms_m = fin.line_n > 0 ? std::sqrt(fin.line_sq / fin.line_n) : res.rms_m;
  int inliers = 0;
  const double c = std::cos(T.theta()), s = std::sin(T.theta());
  for (size_t i = 0; i < scan.points.size(); ++i)
    if (scan.pair(model, i, T * scan.points[i], c, s, o.inlier_distance_m) >= 0) ++inliers;
  res.inlier_ratio = static_cast<double>(inliers) / static_cast<double>(scan.points.size());
  const geometry::SymmetricEigen2 et = geometry::symmetric_eigen(fin.H.topLeftCorner<2, 2>());
  res.weakest_translation_points = et.values(0);
  res.weakest_direction = et.vectors.col(0);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(fin.H);
  if (fin.n >= 10 && es.eigenvalues()(0) > 1e-9) {
    const double sigma = std::max(o.point_sigma_m, res.rms_m);
    res.covariance = o.covariance_inflation * sigma * sigma * fin.H.inverse();
    res.ok = true;
  } else if (fin.n >= 10) {
    // Degenerate (e.g. featureless corridor): huge variance along the unobserved direction.
    Eigen::Vector3d ev = es.eigenvalues().cwiseMax(1e-9);
    const double sigma = std::max(o.point_sigma_m, res.rms_m);
    res.covariance = o.covariance_inflation * sigma * sigma * es.eigenvectors() *
                     ev.cwiseInverse().cwiseMin(1e6).asDiagonal() * es.eigenvectors().transpose();
    res.ok = true;
  }
  res.fit_covariance = res.covariance;
  if (res.ok && res.weakest_translation_points < o.degenerate_min_points) {
    const Eigen::Vector2d& v = res.weakest_direction;
    res.covariance.topLeftCorner<2, 2>() += o.degenerate_variance_m2 * v * v.transpose();
  }
  return res;
}

}  // namespace

IcpResult icp_point_to_line(const Points& scan, const PointMap& model, const Pose2& guess, const IcpOptions& o)
{
  return register_scan(ScanSide{scan}, model, guess, o);
}

IcpResult icp_point_to_line(const Points& scan, const Points& scan_normals, const std::vector<char>& scan_has_normal,
                            const PointMap& model, const Pose2& guess, const IcpOptions& o)
{
  if (scan_normals.size() != scan.size() || scan_has_normal.size() != scan.size() || o.max_normal_angle_deg >= 180.0)
    return register_scan(ScanSide{scan}, model, guess, o);
  return register_scan(ScanSide{scan, &scan_normals, &scan_has_normal, std::cos(o.max_normal_angle_deg * M_PI / 180.0)},
                       model, guess, o);
}

}  // namespace rgnav::scan_mapper
