#include "localizer/scan_model.h"

#include <cmath>

namespace rgnav::localizer {

std::vector<Eigen::Vector2d> beam_end_points(const sensors::LaserScan& scan, const geometry::Pose2& base_from_laser, int beams,
                                             double min_range)
{
  std::vector<Eigen::Vector2d> out;
  const size_t n = scan.size();
  if (n == 0 || beams <= 0) return out;
  const double step = std::max(1.0, static_cast<double>(n) / beams);
  out.reserve(static_cast<size_t>(beams));
  for (double k = 0.5 * step; k < static_cast<double>(n); k += step) {
    const size_t i = static_cast<size_t>(k);
    if (!scan.hit(i) || !std::isfinite(scan.ranges[i]) || scan.ranges[i] < min_range) continue;
    out.push_back(base_from_laser * scan.point(i));
  }
  return out;
}

BeamScorer::BeamScorer(double sigma, double z_hit, double z_rand, double max_distance)
{
  const size_t n = static_cast<size_t>(std::ceil(max_distance * kStepsPerMetre)) + 1;
  table_.resize(n);
  const double norm = z_hit + z_rand;
  for (size_t i = 0; i < n; ++i) {
    const double d = (static_cast<double>(i) + 0.5) / kStepsPerMetre;
    table_[i] = std::log((z_hit * std::exp(-d * d / (2 * sigma * sigma)) + z_rand) / norm);
  }
}

double BeamScorer::score(const LikelihoodField& field, const geometry::Pose2& region_from_base,
                         const std::vector<Eigen::Vector2d>& base_points) const
{
  const Eigen::Matrix2d r = region_from_base.rotation();
  const Eigen::Vector2d& t = region_from_base.translation();
  double s = 0;
  for (const auto& p : base_points) s += log_p(field.distance(t + r * p));
  return s;
}

double BeamScorer::inlier_ratio(const LikelihoodField& field, const geometry::Pose2& region_from_base,
                                const std::vector<Eigen::Vector2d>& base_points, double inlier_distance)
{
  if (base_points.empty()) return 0;
  const Eigen::Matrix2d r = region_from_base.rotation();
  const Eigen::Vector2d& t = region_from_base.translation();
  int in = 0;
  for (const auto& p : base_points) in += field.distance(t + r * p) <= inlier_distance;
  return static_cast<double>(in) / static_cast<double>(base_points.size());
}

}  // namespace rgnav::localizer
