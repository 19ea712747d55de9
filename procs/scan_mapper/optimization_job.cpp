#include "scan_mapper/optimization_job.h"

namespace rgnav::scan_mapper {

OptimizationJob::Verdict OptimizationJob::judge() const
{
  const size_t batch = graph.edges().size() - first_closure;
  if (strain > max_strain_chi2 * static_cast<double>(batch)) return Verdict::kStrained;
  for (size_t k = first_closure; k < graph.edges().size(); ++k)
    if (graph.edge_chi2(graph.edges()[k]) > max_residual_chi2) return Verdict::kInconsistent;
  return Verdict::kHolds;
}

void OptimizationJob::run()
{
  const double before = graph.edges_cost(0, first_closure, options);
  // Each earlier closure's own share of that, should it have to be taken out.
  std::vector<double> closure_before(prune_earlier ? first_closure : 0, 0.0);
  for (size_t k = 0; k < closure_before.size(); ++k)
    if (graph.edges()[k].robust) closure_before[k] = graph.edges_cost(k, k + 1, options);
  summary = graph.optimize(options);
  strain = graph.edges_cost(0, first_closure, options) - before;
  verdict = judge();
  if (!prune_earlier || verdict == Verdict::kInconsistent) return;
  // The strain on what would stay: a false closure resisting a true one is no witness against it.
  std::vector<size_t> doubtful;
  double kept_before = before, doubtful_rise = 0.0;
  for (size_t k = 0; k < first_closure; ++k) {
    const PoseGraphEdge& e = graph.edges()[k];
    if (!e.robust || graph.edge_chi2(e) <= max_residual_chi2) continue;
    doubtful.push_back(k);
    kept_before -= closure_before[k];
    doubtful_rise += graph.edges_cost(k, k + 1, options) - closure_before[k];
  }
  const size_t batch = graph.edges().size() - first_closure;
  if (doubtful.empty() || strain - doubtful_rise > max_strain_chi2 * static_cast<double>(batch)) return;
  for (auto k = doubtful.rbegin(); k != doubtful.rend(); ++k) {
    pruned.emplace_back(graph.edges()[*k].from, graph.edges()[*k].to);
    graph.remove_edge(*k);
    --first_closure;
  }
  summary = graph.optimize(options);
  strain = graph.edges_cost(0, first_closure, options) - kept_before;
  verdict = judge();
}

}  // namespace rgnav::scan_mapper
