// The scan mapper's planar poses are common/geometry/pose2.h; these are the few operations
// on them the mapper needs beyond the class (increments as vectors for the Kalman filter;
// interpolation of odometry is geometry::interpolate).
#pragma once

#include <Eigen/Core>

#include <cmath>

#include "geometry/pose2.h"
#include "geometry/pose_track.h"

namespace rgnav::scan_mapper {

using geometry::normalize_angle;
using geometry::Pose2;

// a_from_b given map_from_a and map_from_b.
inline Pose2 between(const Pose2& map_from_a, const Pose2& map_from_b) { return map_from_a.between(map_from_b); }

inline double translation_norm(const Pose2& p) { return p.translation().norm(); }

inline Eigen::Vector3d to_vector(const Pose2& p) { return {p.x(), p.y(), p.theta()}; }
inline Pose2 pose_from_vector(const Eigen::Vector3d& v) { return Pose2(v.x(), v.y(), v.z()); }

using geometry::interpolate;

}  // namespace rgnav::scan_mapper
