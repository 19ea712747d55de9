// Graph part of the RG map benchmark's metrics (rgmap_metrics.h): exact isomorphism of small
// undirected graphs and the edge-by-edge comparison of a region graph with the room graph.
#include "rgmap_metrics.h"

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <vector>

namespace rgnav::rgmap_pipeline {

void Graph::add_edge(int64_t a, int64_t b)
{
  nodes.insert(a);
  nodes.insert(b);
  if (a != b) edges.insert({std::min(a, b), std::max(a, b)});
}

namespace {

struct Dense
{
  int n = 0;
  std::vector<std::vector<char>> adj;
  std::vector<std::vector<int>> nbr;
};

Dense dense_of(const Graph& g)
{
  Dense d;
  std::map<int64_t, int> index;
  for (int64_t v : g.nodes) index[v] = d.n++;
  d.adj.assign(static_cast<size_t>(d.n), std::vector<char>(static_cast<size_t>(d.n), 0));
  d.nbr.resize(static_cast<size_t>(d.n));
  for (const auto& [a, b] : g.edges) {
    const int i = index.at(a), j = index.at(b);
    d.adj[i][j] = d.adj[j][i] = 1;
    d.nbr[i].push_back(j);
    d.nbr[j].push_back(i);
  }
  return d;
}

// Colour refinement (1-dimensional Weisfeiler-Leman) on both graphs together, so colours are
// comparable: isomorphic graphs end with the same colour histogram, and an isomorphism maps
// every node to a node of its own colour.
void refine(const Dense& a, const Dense& b, std::vector<int>* ca, std::vector<int>* cb)
{
  ca->assign(static_cast<size_t>(a.n), 0);
  cb->assign(static_cast<size_t>(b.n), 0);
  for (int round = 0; round < a.n + b.n + 1; ++round) {
    std::map<std::pair<int, std::vector<int>>, int> palette;
    auto signature = [](const Dense& g, const std::vector<int>& c, int v) {
      std::vector<int> s;
      for (int u : g.nbr[static_cast<size_t>(v)]) s.push_back(c[static_cast<size_t>(u)]);
      std::sort(s.begin(), s.end());
      return std::make_pair(c[static_cast<size_t>(v)], s);
    };
    std::vector<std::pair<int, std::vector<int>>> sa, sb;
    for (int v = 0; v < a.n; ++v) sa.push_back(signature(a, *ca, v));
    for (int v = 0; v < b.n; ++v) sb.push_back(signature(b, *cb, v));
    for (const auto& s : sa) palette.emplace(s, 0);
    for (const auto& s : sb) palette.emplace(s, 0);
    int next = 0;
    for (auto& [k, c] : palette) c = next++;
    std::vector<int> na, nb;
    for (const auto& s : sa) na.push_back(palette.at(s));
    for (const auto& s : sb) nb.push_back(palette.at(s));
    const bool stable = std::set<int>(na.begin(), na.end()).size() + std::set<int>(nb.begin(), nb.end()).size() ==
                        std::set<int>(ca->begin(), ca->end()).size() + std::set<int>(cb->begin(), cb->end()).size();
    *ca = std::move(na);
    *cb = std::move(nb);
    if (stable && round > 0) break;
  }
}

}  // namespace

bool isomorphic(const Graph& ga, const Graph& gb)
{
  if (ga.nodes.size() != gb.nodes.size() || ga.edges.size() != gb.edges.size()) return false;
  const Dense a = dense_of(ga), b = dense_of(gb);
  std::vector<int> ca, cb;
  refine(a, b, &ca, &cb);
  std::vector<int> ha = ca, hb = cb;
  std::sort(ha.begin(), ha.end());
  std::sort(hb.begin(), hb.end());
  if (ha != hb) return false;
  // Backtracking: nodes of a in order of rarest colour first; candidates of the same colour
  // whose adjacency to every node mapped so far agrees.
  std::map<int, int> freq;
  for (int c : ca) ++freq[c];
  std::vector<int> order(static_cast<size_t>(a.n));
  for (int v = 0; v < a.n; ++v) order[static_cast<size_t>(v)] = v;
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return freq[ca[x]] < freq[ca[y]]; });
  std::vector<int> to(static_cast<size_t>(a.n), -1);
  std::vector<char> used(static_cast<size_t>(b.n), 0);
  std::function<bool(size_t)> extend = [&](size_t k) -> bool {
    if (k == order.size()) return true;
    const int v = order[k];
    for (int w = 0; w < b.n; ++w) {
      if (used[static_cast<size_t>(w)] || cb[static_cast<size_t>(w)] != ca[static_cast<size_t>(v)]) continue;
      bool ok = true;
      for (size_t j = 0; j < k && ok; ++j) {
        const int u = order[j];
        ok = a.adj[v][u] == b.adj[w][to[static_cast<size_t>(u)]];
      }
      if (!ok) continue;
      to[static_cast<size_t>(v)] = w;
      used[static_cast<size_t>(w)] = 1;
      if (extend(k + 1)) return true;
      used[static_cast<size_t>(w)] = 0;
    }
    to[static_cast<size_t>(v)] = -1;
    return false;
  };
  return extend(0);
}

GraphComparison compare_graphs(const Graph& truth, const Graph& map, const std::map<int64_t, int64_t>& map_to_truth)
{
  GraphComparison c;
  c.isomorphic = isomorphic(truth, map);
  c.truth_nodes = static_cast<int>(truth.nodes.size());
  c.map_nodes = static_cast<int>(map.nodes.size());
  c.truth_edges = static_cast<int>(truth.edges.size());
  c.map_edges = static_cast<int>(map.edges.size());
  std::set<std::pair<int64_t, int64_t>> hit;
  for (const auto& [u, v] : map.edges) {
    const auto mu = map_to_truth.find(u), mv = map_to_truth.find(v);
    if (mu == map_to_truth.end() || mv == map_to_truth.end()) {
      ++c.edges_extra;
      continue;
    }
    if (mu->second == mv->second) {
      ++c.edges_internal;
      continue;
    }
    const std::pair<int64_t, int64_t> e{std::min(mu->second, mv->second), std::max(mu->second, mv->second)};
    if (truth.edges.count(e)) hit.insert(e);
    else ++c.edges_extra;
  }
  c.edges_matched = static_cast<int>(hit.size());
  c.edges_missing = c.truth_edges - c.edges_matched;
  std::set<int64_t> reached;
  for (const auto& [r, t] : map_to_truth) reached.insert(t);
  for (int64_t t : truth.nodes)
    if (!reached.count(t)) ++c.rooms_unmatched;
  return c;
}

}  // namespace rgnav::rgmap_pipeline
