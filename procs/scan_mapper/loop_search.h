// The two checks that keep false loop closures out of the pose graph (no LCM):
//
//  - Uncertainty along the graph: how well the relative pose of an old node and the current
//    one is known is read off the graph itself, by a Dijkstra search from the current node
//    that adds up a drift model's variances edge by edge (sequential edges: random-walk
//    growth with distance and turn; closure edges: their own covariance). Right after a
//    closure the old part of the map is close in this sense, however long the path was; after
//    a long excursion it is far. Candidates are gated by this uncertainty and the correlative
//    search window grows with it, so a closure is searched where it can be, and only there.
//  - Pairwise consistency of closure hypotheses (as in Olson's single-cluster graph
//    partitioning, reduced to pairs): two closures found from different current scans must
//    agree with each other through the locally accurate odometry/scan-matching chain between
//    the two current scans and the old estimate between their two anchors. A look-alike place
//    rarely yields two mutually consistent matches from views far enough apart to differ (the
//    next scan, a step on, repeats the first's match, look-alike or not); the true place always does.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scan_mapper/pose_graph.h"

namespace rgnav::scan_mapper {

struct DriftModel
{
  // Random-walk drift of the local registration, as variances per unit of motion.
  double trans_var_per_m = 0.0025;    // [m^2/m]  (0.05 m after 1 m)
  double rot_var_per_m = 1e-4;        // [rad^2/m] (0.01 rad after 1 m)
  double rot_var_per_rad = 4e-4;      // [rad^2/rad]
};

// Relative uncertainty of a node with respect to the search origin.
struct RelativeUncertainty
{
  double var_rot = -1.0;    // [rad^2]; < 0: not reached
  double var_trans = 0.0;   // [m^2] along-path translation noise
  double length_m = 0.0;    // path length along the cheapest chain
  bool reached() const { return var_rot >= 0.0; }
  // Position standard deviation: translation noise plus the lever arm of the heading error
  // integrated along the path (random walk heading: lateral variance var_rot * L^2 / 3).
  double sigma_xy() const { return std::sqrt(var_trans + var_rot * length_m * length_m / 3.0); }
  double sigma_rot() const { return std::sqrt(std::max(0.0, var_rot)); }
};

// Dijkstra from `origin` over the graph's edges, cost = accumulated heading variance.
std::vector<RelativeUncertainty> relative_uncertainty(const PoseGraph& graph, int origin, const DriftModel& drift);

// A loop-closure hypothesis: node `node` seen from old node `anchor` at anchor_from_node.
struct ClosureHypothesis
{
  int node = -1, anchor = -1;
  Pose2 anchor_from_node;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // in the frame of anchor_from_node
  bool direct = false;  // agrees with a well-known relative pose: needs no witness
  double path_m = 0.0;  // the node's odometry path length (ScanNode::path_m)
};

struct ConsistencyTolerance
{
  double trans_m = 0.3;
  double rot_rad = 0.05;
};

// Whether a and b agree: the pose of b.node relative to a.node predicted through the two
// anchors (the closures and the current estimate between the anchors) against the current
// estimate between the two nodes.
bool pairwise_consistent(const PoseGraph& graph, const ClosureHypothesis& a, const ClosureHypothesis& b,
                         const ConsistencyTolerance& tol);

// Whether b is a witness for a: consistent with it, and found from a scan at least min_travel_m
// along the path from a's. Two scans a step apart see the same walls from nearly the same spot;
// whatever look-alike the first fitted, the second fits too, and the two agree by construction.
// Agreement is evidence only between views that could have disagreed.
bool witnesses(const PoseGraph& graph, const ClosureHypothesis& a, const ClosureHypothesis& b,
               const ConsistencyTolerance& tol, double min_travel_m);

}  // namespace rgnav::scan_mapper
