#include "scan_mapper/pose_graph.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <cmath>

namespace rgnav::scan_mapper {
namespace {

Eigen::Matrix2d rot(double th)
{
  const double c = std::cos(th), s = std::sin(th);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  return R;
}

// Kernels on the squared Mahalanobis distance s: rho(s) and the IRLS weight rho'(s).
double robust_weight(double s, const OptimizerOptions& o)
{
  const double c = o.robust_scale;
  if (o.kernel == RobustKernel::kCauchy) return 1.0 / (1.0 + s / (c * c));
  return s <= c * c ? 1.0 : c / std::sqrt(s);
}
double robust_rho(double s, const OptimizerOptions& o)
{
  const double c = o.robust_scale;
  if (o.kernel == RobustKernel::kCauchy) return c * c * std::log1p(s / (c * c));
  return s <= c * c ? s : 2.0 * c * std::sqrt(s) - c * c;
}

}  // namespace

Eigen::Vector3d edge_error(const Pose2& a, const Pose2& b, const Pose2& z)
{
  const Eigen::Matrix2d Ra = rot(a.theta()), Rz = rot(z.theta());
  const Eigen::Vector2d t = Rz.transpose() * (Ra.transpose() * Eigen::Vector2d(b.x() - a.x(), b.y() - a.y()) - Eigen::Vector2d(z.x(), z.y()));
  return {t.x(), t.y(), normalize_angle(b.theta() - a.theta() - z.theta())};
}

int PoseGraph::add_node(const Pose2& p)
{
  poses_.push_back(p);
  return static_cast<int>(poses_.size()) - 1;
}

void PoseGraph::add_edge(const PoseGraphEdge& e) { edges_.push_back(e); }

double PoseGraph::edge_chi2(const PoseGraphEdge& e) const
{
  const Eigen::Vector3d r = edge_error(pose(e.from), pose(e.to), e.from_from_to);
  return r.dot(e.information * r);
}

double PoseGraph::edge_weight(const PoseGraphEdge& e, const OptimizerOptions& o) const
{
  return e.robust ? robust_weight(edge_chi2(e), o) : 1.0;
}

double PoseGraph::edges_cost(size_t first, size_t last, const OptimizerOptions& o) const
{
  double c = 0.0;
  for (size_t k = first; k < last && k < edges_.size(); ++k) {
    const auto& e = edges_[k];
    const double s = edge_chi2(e);
    c += e.robust ? robust_rho(s, o) : s;
  }
  return c;
}

double PoseGraph::cost(const std::vector<Pose2>& poses, const OptimizerOptions& o) const
{
  double c = 0.0;
  for (const auto& e : edges_) {
    const Eigen::Vector3d r = edge_error(poses[static_cast<size_t>(e.from)], poses[static_cast<size_t>(e.to)], e.from_from_to);
    const double s = r.dot(e.information * r);
    c += e.robust ? robust_rho(s, o) : s;
  }
  return c;
}

OptimizerSummary PoseGraph::optimize(const OptimizerOptions& o)
{
  OptimizerSummary sum;
  const int n = static_cast<int>(poses_.size());
  if (n < 2 || edges_.empty()) return sum;
  // Node 0 is the fixed origin: variables are nodes 1..n-1.
  const int dim = 3 * (n - 1);
  double current = cost(poses_, o);
  sum.initial_cost = current;
  double lambda = 1e-4;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool pattern_done = false;
  for (int it = 0; it < o.max_iterations; ++it) {
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(edges_.size() * 36 + static_cast<size_t>(dim));
    Eigen::VectorXd b = Eigen::VectorXd::Zero(dim);
    for (const auto& e : edges_) {
      const Pose2& a = poses_[static_cast<size_t>(e.from)];
      const Pose2& c = poses_[static_cast<size_t>(e.to)];
      const Eigen::Vector3d r = edge_error(a, c, e.from_from_to);
      const double w = e.robust ? robust_weight(r.dot(e.information * r), o) : 1.0;
      const Eigen::Matrix2d Ra = rot(a.theta()), Rz = rot(e.from_from_to.theta());
      const Eigen::Vector2d dt(c.x() - a.x(), c.y() - a.y());
      Eigen::Matrix2d dRaT;  // d(Ra^T)/dtheta_a
      dRaT << -std::sin(a.theta()), std::cos(a.theta()), -std::cos(a.theta()), -std::sin(a.theta());
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
      A.block<2, 2>(0, 0) = -Rz.transpose() * Ra.transpose();
      A.block<2, 1>(0, 2) = Rz.transpose() * dRaT * dt;
      A(2, 2) = -1.0;
      B.block<2, 2>(0, 0) = Rz.transpose() * Ra.transpose();
      B(2, 2) = 1.0;
      const Eigen::Matrix3d Om = w * e.information;
      const int ia = 3 * (e.from - 1), ib = 3 * (e.to - 1);
      const Eigen::Matrix3d Haa = A.transpose() * Om * A, Hab = A.transpose() * Om * B, Hbb = B.transpose() * Om * B;
      const Eigen::Vector3d ba = A.transpose() * Om * r, bb = B.transpose() * Om * r;
      auto put = [&](int i0, int j0, const Eigen::Matrix3d& M) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) trip.emplace_back(i0 + i, j0 + j, M(i, j));
      };
      if (e.from > 0) {
        put(ia, ia, Haa);
        b.segment<3>(ia) += ba;
      }
      if (e.to > 0) {
        put(ib, ib, Hbb);
        b.segment<3>(ib) += bb;
      }
      if (e.from > 0 && e.to > 0) {
        put(ia, ib, Hab);
        put(ib, ia, Hab.transpose());
      }
    }
    Eigen::SparseMatrix<double> H(dim, dim);
    H.setFromTriplets(trip.begin(), trip.end());
    // Levenberg-Marquardt: retry with more damping until the cost drops.
    bool improved = false;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Eigen::SparseMatrix<double> Hd = H;
      for (int i = 0; i < dim; ++i) Hd.coeffRef(i, i) += lambda * (1.0 + H.coeff(i, i));
      if (!pattern_done) {
        solver.analyzePattern(Hd);
        pattern_done = true;
      }
      solver.factorize(Hd);
      if (solver.info() != Eigen::Success) {
        lambda *= 10.0;
        continue;
      }
      const Eigen::VectorXd dx = -solver.solve(b);
      std::vector<Pose2> trial = poses_;
      for (int k = 1; k < n; ++k) {
        auto& p = trial[static_cast<size_t>(k)];
        p = Pose2{p.x() + dx(3 * (k - 1)), p.y() + dx(3 * (k - 1) + 1), normalize_angle(p.theta() + dx(3 * (k - 1) + 2))};
      }
      const double tc = cost(trial, o);
      if (tc < current) {
        poses_ = std::move(trial);
        const double rel = (current - tc) / std::max(current, 1e-12);
        current = tc;
        lambda = std::max(1e-9, lambda * 0.2);
        improved = true;
        sum.iterations = it + 1;
        if (rel < o.converged_relative) it = o.max_iterations;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;
  }
  sum.final_cost = current;
  return sum;
}

}  // namespace rgnav::scan_mapper
