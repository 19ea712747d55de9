#include "scan_mapper/relations_metric.h"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>

namespace rgnav::scan_mapper {

std::vector<std::pair<size_t, size_t>> select_relations(const std::vector<TimedPose>& ref, const RelationOptions& o)
{
  std::vector<std::pair<size_t, size_t>> out;
  for (size_t i = 0; i + 1 < ref.size(); ++i) out.emplace_back(i, i + 1);
  const double d2 = o.max_distance_m * o.max_distance_m;
  const auto min_dt = static_cast<int64_t>(o.min_dt_s * 1e6);
  for (size_t i = 0; i < ref.size(); ++i)
    for (size_t j = i + 2; j < ref.size(); ++j) {
      if (ref[j].utime - ref[i].utime <= min_dt) continue;
      const double dx = ref[j].pose.x() - ref[i].pose.x(), dy = ref[j].pose.y() - ref[i].pose.y();
      if (dx * dx + dy * dy < d2) out.emplace_back(i, j);
    }
  return out;
}

RelationError relation_error(const std::vector<Pose2>& est, const std::vector<Pose2>& ref,
                             const std::vector<std::pair<size_t, size_t>>& rel)
{
  if (est.size() != ref.size()) throw std::invalid_argument("relation_error: trajectories differ in length");
  RelationError r;
  double st = 0, st2 = 0, sr = 0, sr2 = 0;
  for (const auto& [i, j] : rel) {
    const Pose2 de = between(est[i], est[j]);
    const Pose2 dr = between(ref[i], ref[j]);
    const Pose2 e = between(dr, de);  // dr^-1 * de
    const double t = translation_norm(e);
    const double a = std::fabs(e.theta()) * 180.0 / M_PI;
    st += t, st2 += t * t, sr += a, sr2 += a * a;
    ++r.count;
  }
  if (r.count == 0) return r;
  const double n = static_cast<double>(r.count);
  r.trans_mean_m = st / n;
  r.rot_mean_deg = sr / n;
  r.trans_std_m = std::sqrt(std::max(0.0, st2 / n - r.trans_mean_m * r.trans_mean_m));
  r.rot_std_deg = std::sqrt(std::max(0.0, sr2 / n - r.rot_mean_deg * r.rot_mean_deg));
  return r;
}

double ate_rmse(const std::vector<Pose2>& est, const std::vector<Pose2>& ref)
{
  if (est.size() != ref.size()) throw std::invalid_argument("ate_rmse: trajectories differ in length");
  if (est.empty()) return 0.0;
  const double n = static_cast<double>(est.size());
  Eigen::Vector2d me = Eigen::Vector2d::Zero(), mr = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < est.size(); ++k) {
    me += Eigen::Vector2d(est[k].x(), est[k].y());
    mr += Eigen::Vector2d(ref[k].x(), ref[k].y());
  }
  me /= n;
  mr /= n;
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
  for (size_t k = 0; k < est.size(); ++k)
    C += (Eigen::Vector2d(ref[k].x(), ref[k].y()) - mr) * (Eigen::Vector2d(est[k].x(), est[k].y()) - me).transpose();
  Eigen::JacobiSVD<Eigen::Matrix2d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix2d D = Eigen::Matrix2d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) D(1, 1) = -1;
  const Eigen::Matrix2d R = svd.matrixU() * D * svd.matrixV().transpose();  // ref ≈ R est + t
  const Eigen::Vector2d t = mr - R * me;
  double s = 0.0;
  for (size_t k = 0; k < est.size(); ++k)
    s += (R * Eigen::Vector2d(est[k].x(), est[k].y()) + t - Eigen::Vector2d(ref[k].x(), ref[k].y())).squaredNorm();
  return std::sqrt(s / n);
}

}  // namespace rgnav::scan_mapper
