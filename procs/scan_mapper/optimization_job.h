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
  // Acceptance (LoopClosureOptions): a new closure the optimised graph still disagrees with
  // (chi2 above max_residual_chi2), or a batch the rest of the graph has to bend for (strain
  // above max_strain_chi2 per closure), is most likely false: a look-alike place.
  double max_residual_chi2 = 25.0;
  double max_strain_chi2 = 100.0;
  // With prune_earlier, a batch that holds also takes out earlier closures the optimised graph
  // disagrees with by more than max_residual_chi2, and the graph is optimised again. A false
  // closure adopted while the graph could not yet tell otherwise stays for good, held down
  // only by the robust kernel, and counts in the strain of every true closure that
  // contradicts it (the strain that decides leaves it out).
  bool prune_earlier = false;
  enum class Verdict { kHolds, kInconsistent, kStrained };
  Verdict verdict = Verdict::kHolds;        // of the new closures, set by run()
  std::vector<std::pair<int, int>> pruned;  // (from, to) of the earlier closures taken out
  void run();

 private:
  Verdict judge() const;
};

}  // namespace rgnav::scan_mapper
