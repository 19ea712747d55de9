#include "scan_mapper/icp.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace rgnav::scan_mapper {
namespace {

struct Normal
{
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double sq = 0.0;
  int n = 0;

  void add(const Eigen::Vector3d& J, double r, double w)
  {
    H += w * J * J.transpose();
    g += w * J * r;
    sq += r * r;
    ++n;
  }
};

// Accumulates the Gauss-Newton system for the correspondences within max_dist.
Normal linearize(const Points& scan, const PointMap& model, const Pose2& T, double max_dist)
{
  Normal ne;
  const double c = std::cos(T.theta()), s = std::sin(T.theta());
  for (const auto& q : scan) {
    const Eigen::Vector2d p(T.x() + c * q.x() - s * q.y(), T.y() + s * q.x() + c * q.y());
    const int j = model.nearest(p, max_dist);
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
    } else {
      const double w = d.norm() <= k ? 1.0 : k / d.norm();
      ne.add(Eigen::Vector3d(1.0, 0.0, dp_dth.x()), d.x(), w);
      ne.add(Eigen::Vector3d(0.0, 1.0, dp_dth.y()), d.y(), w);
      --ne.n;
    }
  }
  return ne;
}

}  // namespace

IcpResult icp_point_to_line(const Points& scan, const PointMap& model, const Pose2& guess, const IcpOptions& o)
{
  IcpResult res;
  res.map_from_scan = guess;
  if (scan.size() < 5 || model.size() < 5) return res;
  Pose2 T = guess;
  double max_dist = o.initial_max_distance_m;
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    const Normal ne = linearize(scan, model, T, max_dist);
    if (ne.n < 5) break;
    // Small Levenberg damping keeps degenerate directions (a corridor) where the guess put them.
    Eigen::Matrix3d H = ne.H;
    H.diagonal() += Eigen::Vector3d(1e-6, 1e-6, 1e-6) * std::max(1.0, H.trace());
    const Eigen::Vector3d delta = -H.ldlt().solve(ne.g);
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
  int inliers = 0;
  for (const auto& q : scan)
    if (model.nearest(T * q, o.inlier_distance_m) >= 0) ++inliers;
  res.inlier_ratio = static_cast<double>(inliers) / static_cast<double>(scan.size());
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
  return res;
}

}  // namespace rgnav::scan_mapper
