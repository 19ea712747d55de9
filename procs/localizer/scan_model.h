// Scoring a scan against a region's distance field: the likelihood-field model's log p per beam
// end point, p(d) = z_hit exp(-d^2 / 2 sigma^2) + z_rand (1 at d = 0), from a lookup table.
// Beams without a return carry no end point and are left out.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "geometry/pose2.h"
#include "localizer/likelihood_field.h"
#include "sensors/laser_scan.h"

namespace rgnav::localizer {

// End points of up to `beams` returns spread evenly over the scan, in the base frame. Returns
// closer than `min_range` are left out: something touching the robot (a person brushing past)
// hides the map, it is not part of it.
std::vector<Eigen::Vector2d> beam_end_points(const sensors::LaserScan& scan, const geometry::Pose2& base_from_laser, int beams,
                                             double min_range = 0.0);

class BeamScorer
{
 public:
  BeamScorer(double sigma, double z_hit, double z_rand, double max_distance);

  double log_p(float distance) const
  {
    const size_t i = static_cast<size_t>(distance * kStepsPerMetre);
    return table_[i < table_.size() ? i : table_.size() - 1];
  }
  // Sum of log p of the end points placed at region_from_base.
  double score(const LikelihoodField& field, const geometry::Pose2& region_from_base,
               const std::vector<Eigen::Vector2d>& base_points) const;
  // Share of end points within `inlier_distance` of a line.
  static double inlier_ratio(const LikelihoodField& field, const geometry::Pose2& region_from_base,
                             const std::vector<Eigen::Vector2d>& base_points, double inlier_distance);
  double floor() const { return table_.back(); }   // log p of a beam far from every line

 private:
  static constexpr double kStepsPerMetre = 200.0;
  std::vector<double> table_;
};

}  // namespace rgnav::localizer
