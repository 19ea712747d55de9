// Point-to-line ICP (Gauss-Newton on x, y, theta) with a correspondence rejection threshold
// that decays exponentially over the iterations (Holz et al. 2010, sec. 6.3): generous at
// first for convergence from a rough guess, tight at the end for a precise fit. Points
// whose model neighbourhood is not line-like use point-to-point residuals. Given the scan's
// normals oriented toward its sensor (and the model's likewise), a scan point only pairs with
// model points seen from the same side: the two faces of a thin wall, one seen from a room
// and one from the corridor, are otherwise matched onto each other, which shifts the fit by
// the wall's thickness (observed on loop closures between a room and the corridor beside it).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "scan_mapper/point_map.h"
#include "scan_mapper/pose_math.h"

namespace rgnav::scan_mapper {

struct IcpOptions
{
  int max_iterations = 40;
  double initial_max_distance_m = 0.5;  // rejection threshold of the first iteration
  double final_max_distance_m = 0.08;   // floor the threshold decays to
  double decay = 0.8;                   // threshold factor per iteration
  double converged_translation_m = 1e-4;
  double converged_rotation_rad = 1e-4;
  double inlier_distance_m = 0.1;       // distance counted as agreement in inlier_ratio
  double point_sigma_m = 0.03;          // range noise for the covariance estimate
  double covariance_inflation = 4.0;    // residuals are correlated; the raw estimate is too confident
  double max_normal_angle_deg = 60.0;   // scan and model normals further apart do not pair (180: off)
  // Degeneracy (Zhang, Kaess & Singh, ICRA 2016): a translation direction constrained by fewer
  // surface points than this (a hallway's axis, seen only at a few door jambs) is not measured:
  // the match's variance along it grows by degenerate_variance_m2, so that the Kalman fusion
  // keeps the odometry there, and a loop closure edge found there holds the graph only across
  // the hallway. The Gauss-Newton covariance claims millimetres along such an axis, although a
  // jamb matched to the next door's is off by decimetres. 0: off.
  double degenerate_min_points = 0.0;
  double degenerate_variance_m2 = 1.0;
  // false: the guess's heading is kept and only the translation fitted (the result's covariance
  // is still the full Hessian's, heading terms included: the caller says what the heading is worth).
  bool estimate_rotation = true;
};

struct IcpResult
{
  Pose2 map_from_scan;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // of (x, y, theta) in the map frame
  // The same before the degeneracy terms (IcpOptions::degenerate_*) were added: how precisely
  // the fit itself holds, where covariance also says which directions it may have aliased.
  Eigen::Matrix3d fit_covariance = Eigen::Matrix3d::Identity();
  double inlier_ratio = 0.0;  // share of scan points within inlier_distance_m of the model
  double rms_m = 0.0;         // rms residual of the final correspondences
  // ... of those on surfaces (point-to-line) alone: near the range noise when the fit is right.
  // Point-to-point residuals also hold the spacing of sparse far points, whatever the fit.
  double surface_rms_m = 0.0;
  // Smallest eigenvalue of the translation block of the Gauss-Newton information (unit normals):
  // about how many surface points constrain the weakest direction, and that direction (map frame).
  double weakest_translation_points = 0.0;
  Eigen::Vector2d weakest_direction = Eigen::Vector2d::UnitX();
  int iterations = 0;
  int correspondences = 0;
  bool ok = false;            // enough correspondences for a well-posed solution
};

// scan points are in the scan's own frame; guess is map_from_scan. No normal check.
IcpResult icp_point_to_line(const Points& scan, const PointMap& model, const Pose2& guess,
                            const IcpOptions& options);
// With the scan points' oriented normals (scan frame; has_normal false where there is none,
// those pair with anything), as the model's are (PointMap::nearest with a normal).
IcpResult icp_point_to_line(const Points& scan, const Points& scan_normals, const std::vector<char>& scan_has_normal,
                            const PointMap& model, const Pose2& guess, const IcpOptions& options);

}  // namespace rgnav::scan_mapper
