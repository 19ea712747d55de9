// SLAM accuracy by relative relations (Kuemmerle et al. 2009, "On measuring the accuracy of
// SLAM algorithms"): the error of an estimate is measured on relative poses between pairs of
// poses, so an early error does not dominate everything after it. Pairs are consecutive poses
// plus all pairs closer than max_distance_m and more than min_dt_s apart (loops). Also the
// absolute trajectory error (RMSE after the best rigid alignment).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "scan_mapper/pose_math.h"

namespace rgnav::scan_mapper {

struct TimedPose
{
  int64_t utime = 0;
  Pose2 pose;
};

struct RelationOptions
{
  double max_distance_m = 1.0;
  double min_dt_s = 30.0;
};

// Index pairs (i, j), i < j, into the reference trajectory.
std::vector<std::pair<size_t, size_t>> select_relations(const std::vector<TimedPose>& reference,
                                                        const RelationOptions& options = {});

struct RelationError
{
  size_t count = 0;
  double trans_mean_m = 0.0, trans_std_m = 0.0;
  double rot_mean_deg = 0.0, rot_std_deg = 0.0;
};

// estimate[k] and reference[k] are the same instant.
RelationError relation_error(const std::vector<Pose2>& estimate, const std::vector<Pose2>& reference,
                             const std::vector<std::pair<size_t, size_t>>& relations);

// Root mean square position error after aligning estimate to reference with the best rotation
// and translation (2D Umeyama/Kabsch, no scale).
double ate_rmse(const std::vector<Pose2>& estimate, const std::vector<Pose2>& reference);

}  // namespace rgnav::scan_mapper
