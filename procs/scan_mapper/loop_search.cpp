#include "scan_mapper/loop_search.h"

#include <Eigen/Dense>

#include <cmath>
#include <queue>

namespace rgnav::scan_mapper {

std::vector<RelativeUncertainty> relative_uncertainty(const PoseGraph& graph, int origin, const DriftModel& drift)
{
  const size_t n = graph.size();
  std::vector<RelativeUncertainty> out(n);
  if (origin < 0 || static_cast<size_t>(origin) >= n) return out;
  // Adjacency: edge indices per node.
  std::vector<std::vector<int>> adj(n);
  const auto& edges = graph.edges();
  for (size_t k = 0; k < edges.size(); ++k) {
    adj[static_cast<size_t>(edges[k].from)].push_back(static_cast<int>(k));
    adj[static_cast<size_t>(edges[k].to)].push_back(static_cast<int>(k));
  }
  // Variances an edge adds: closures carry their own covariance, sequential edges the drift model.
  auto edge_vars = [&](const PoseGraphEdge& e, double* vr, double* vt) {
    const double d = translation_norm(e.from_from_to);
    if (e.robust) {
      const Eigen::Matrix3d c = e.information.inverse();
      *vr = std::max(0.0, c(2, 2));
      *vt = std::max(0.0, c(0, 0) + c(1, 1));
    } else {
      *vr = drift.rot_var_per_m * d + drift.rot_var_per_rad * std::fabs(e.from_from_to.theta());
      *vt = drift.trans_var_per_m * d;
    }
  };
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  out[static_cast<size_t>(origin)] = {0.0, 0.0, 0.0};
  queue.push({0.0, origin});
  std::vector<char> done(n, 0);
  while (!queue.empty()) {
    const auto [cost, u] = queue.top();
    queue.pop();
    if (done[static_cast<size_t>(u)]) continue;
    done[static_cast<size_t>(u)] = 1;
    const auto& ru = out[static_cast<size_t>(u)];
    for (const int k : adj[static_cast<size_t>(u)]) {
      const auto& e = edges[static_cast<size_t>(k)];
      const int v = e.from == u ? e.to : e.from;
      if (done[static_cast<size_t>(v)]) continue;
      double vr = 0.0, vt = 0.0;
      edge_vars(e, &vr, &vt);
      auto& rv = out[static_cast<size_t>(v)];
      const double c = ru.var_rot + vr;
      if (!rv.reached() || c < rv.var_rot) {
        rv = {c, ru.var_trans + vt, ru.length_m + translation_norm(e.from_from_to)};
        queue.push({c, v});
      }
    }
  }
  return out;
}

bool pairwise_consistent(const PoseGraph& graph, const ClosureHypothesis& a, const ClosureHypothesis& b,
                         const ConsistencyTolerance& tol)
{
  // Through the anchors: map_from_a.node = map_from_a.anchor * a.anchor_from_node, etc.
  const Pose2 via_a = graph.pose(a.anchor) * a.anchor_from_node;
  const Pose2 via_b = graph.pose(b.anchor) * b.anchor_from_node;
  const Pose2 predicted = between(via_a, via_b);
  const Pose2 chain = between(graph.pose(a.node), graph.pose(b.node));
  const Pose2 d = between(chain, predicted);
  return translation_norm(d) <= tol.trans_m && std::fabs(d.theta()) <= tol.rot_rad;
}

bool witnesses(const PoseGraph& graph, const ClosureHypothesis& a, const ClosureHypothesis& b,
               const ConsistencyTolerance& tol, double min_travel_m)
{
  return std::fabs(b.path_m - a.path_m) >= min_travel_m && pairwise_consistent(graph, a, b, tol);
}

}  // namespace rgnav::scan_mapper
