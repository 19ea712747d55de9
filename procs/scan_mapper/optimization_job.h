// The pose graph optimisation after a loop closure, as a job (ScanMapper, deferred mode).
#pragma once

#include <Eigen/Core>

#include <utility>
#include <vector>

#include "scan_mapper/pose_graph.h"

namespace rgnav::scan_mapper {

// A pose graph optimisation after a loop closure, self-contained so that it can run on another
// thread while the mapper goes on (run() touches nothing but the job).
struct OptimizationJob
{
  PoseGraph graph;             // the mapper's graph plus the closure edges
  size_t first_closure = 0;    // index of the first closure edge in graph.edges()
  int newest = 0;              // the node whose scan found the closures
  int anchor = 0;              // ... and the old node of the last closure
  Eigen::Matrix3d closure_covariance = Eigen::Matrix3d::Zero();  // of the last closure
  OptimizerOptions options;
  OptimizerSummary summary;
  // How much the optimisation raised the cost of the edges that were there before the
  // closures (what the closures force the rest of the map to give).
  double strain = 0.0;
  // Earlier closures the optimised graph disagrees with by more than this chi2 are taken out
  // and the graph optimised again (0: none), once the new closures hold: each within
  // prune_chi2, and the strain on the edges that stay at most max_strain per new closure. A
  // false closure adopted while the graph could not yet tell otherwise stays for good, held
  // down only by the robust kernel, and counts in the strain of every true closure that
  // contradicts it (strain then also leaves it out).
  double prune_chi2 = 0.0;
  double max_strain = 0.0;
  std::vector<std::pair<int, int>> pruned;  // (from, to) of the closures taken out
  void run();
};

}  // namespace rgnav::scan_mapper
