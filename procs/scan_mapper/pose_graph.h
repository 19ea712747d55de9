// A 2D pose graph and its sparse least-squares optimiser: Levenberg-Marquardt with Eigen's
// sparse Cholesky (SimplicialLDLT), the first node held fixed, and a robust kernel (Huber or
// Cauchy) on edges marked robust (loop closures) so that a false closure is down-weighted
// instead of bending the whole map.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "scan_mapper/pose_math.h"

namespace rgnav::scan_mapper {

struct PoseGraphEdge
{
  int from = 0, to = 0;
  Pose2 from_from_to;  // measured relative pose
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  bool robust = false;  // apply the robust kernel
};

enum class RobustKernel { kHuber, kCauchy };

struct OptimizerOptions
{
  int max_iterations = 20;
  RobustKernel kernel = RobustKernel::kHuber;
  double robust_scale = 3.0;      // kernel scale on the Mahalanobis distance (sqrt of chi2)
  double converged_relative = 1e-6;  // stop when the cost changes less than this (relative)
};

struct OptimizerSummary
{
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
};

class PoseGraph
{
 public:
  int add_node(const Pose2& map_from_node);
  void add_edge(const PoseGraphEdge& edge);
  void remove_edge(size_t index) { edges_.erase(edges_.begin() + static_cast<std::ptrdiff_t>(index)); }
  OptimizerSummary optimize(const OptimizerOptions& options);

  size_t size() const { return poses_.size(); }
  const Pose2& pose(int i) const { return poses_[static_cast<size_t>(i)]; }
  void set_pose(int i, const Pose2& p) { poses_[static_cast<size_t>(i)] = p; }
  const std::vector<Pose2>& poses() const { return poses_; }
  const std::vector<PoseGraphEdge>& edges() const { return edges_; }
  // The edge's squared Mahalanobis error at the current poses.
  double edge_chi2(const PoseGraphEdge& e) const;
  // Robust weight an edge currently gets (1 for non-robust edges).
  double edge_weight(const PoseGraphEdge& e, const OptimizerOptions& options) const;
  // The optimiser's cost of edges [first, last) at the current poses (chi2, robust edges
  // through the kernel).
  double edges_cost(size_t first, size_t last, const OptimizerOptions& options) const;

 private:
  double cost(const std::vector<Pose2>& poses, const OptimizerOptions& o) const;

  std::vector<Pose2> poses_;
  std::vector<PoseGraphEdge> edges_;
};

// The error of an edge at the given poses: (from_from_to measured)^-1 * (from^-1 * to).
Eigen::Vector3d edge_error(const Pose2& from, const Pose2& to, const Pose2& measured);

}  // namespace rgnav::scan_mapper
