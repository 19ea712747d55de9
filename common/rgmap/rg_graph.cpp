#include "rgmap/rg_graph.h"

#include <functional>
#include <limits>
#include <map>
#include <queue>

namespace rgnav::rgmap {

RgGraph build_graph(const RgMap& map, const GraphOptions& options)
{
  RgGraph g;
  g.map_version = map.version;
  std::map<int64_t, std::vector<size_t>> nodes_of_region;
  int64_t next_id = 1;
  auto add_node = [&](int64_t region, int64_t gateway, const Eigen::Vector2d& p) {
    g.nodes.push_back({next_id++, region, gateway, p});
    nodes_of_region[region].push_back(g.nodes.size() - 1);
    return g.nodes.back().id;
  };
  for (const auto& [gid, gw] : map.gateways()) {
    if (gw.neutralized) continue;  // no longer separates two regions
    const int64_t a = map.resolve(gw.region_a);
    const int64_t b = gw.region_b ? map.resolve(gw.region_b) : 0;
    for (const auto& c : gw.crossing_points) {
      const int64_t na = add_node(a, gid, c);
      if (b == 0) continue;
      const int64_t nb = add_node(b, gid, gw.region_a_from_region_b.inverse() * c);
      const double t = gw.traversals > 0 ? gw.mean_traversal_time : options.gateway_crossing_time;
      g.edges.push_back({na, nb, GraphEdge::Kind::kGateway, 0, gid, t, 0.0});
    }
  }
  for (const auto& [region, idx] : nodes_of_region) {
    for (size_t i = 0; i < idx.size(); ++i) {
      for (size_t j = i + 1; j < idx.size(); ++j) {
        const auto& u = g.nodes[idx[i]];
        const auto& v = g.nodes[idx[j]];
        const double len = (u.point - v.point).norm();
        g.edges.push_back({u.id, v.id, GraphEdge::Kind::kRegion, region, 0, len / options.nominal_speed, len});
      }
    }
  }
  return g;
}

std::vector<int64_t> shortest_path(const RgGraph& graph, int64_t from_node, int64_t to_node)
{
  std::map<int64_t, std::vector<std::pair<int64_t, double>>> adj;
  for (const auto& e : graph.edges) {
    adj[e.from].push_back({e.to, e.cost});
    adj[e.to].push_back({e.from, e.cost});
  }
  std::map<int64_t, double> dist;
  std::map<int64_t, int64_t> prev;
  using Item = std::pair<double, int64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[from_node] = 0;
  open.push({0, from_node});
  while (!open.empty()) {
    const auto [d, u] = open.top();
    open.pop();
    if (d > dist[u]) continue;
    if (u == to_node) break;
    for (const auto& [v, c] : adj[u]) {
      const double nd = d + c;
      auto it = dist.find(v);
      if (it == dist.end() || nd < it->second) {
        dist[v] = nd;
        prev[v] = u;
        open.push({nd, v});
      }
    }
  }
  if (!dist.count(to_node)) return {};
  std::vector<int64_t> path{to_node};
  while (path.back() != from_node) path.push_back(prev.at(path.back()));
  return {path.rbegin(), path.rend()};
}

}  // namespace rgnav::rgmap
