// The RG graph (diss. 2, 5.4): nodes are the crossing points of gateways, one per adjacent
// region (in that region's frame); edges are traversals of a region between two of its
// crossing points, or of a gateway between its two sides. Costs are expected times: Euclidean
// length over a nominal speed at first, the learned mean time of a gateway once traversed.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::rgmap {

struct GraphNode
{
  int64_t id = 0;
  int64_t region_id = 0;
  int64_t gateway_id = 0;
  Eigen::Vector2d point{0, 0};   // region frame
};

struct GraphEdge
{
  enum class Kind : int8_t { kRegion = 1, kGateway = 2 };
  int64_t from = 0, to = 0;      // node ids
  Kind kind = Kind::kRegion;
  int64_t region_id = 0;         // kRegion
  int64_t gateway_id = 0;        // kGateway
  double cost = 0;               // [s]
  double length = 0;             // [m]
};

struct RgGraph
{
  int64_t map_version = 0;
  std::vector<GraphNode> nodes;
  std::vector<GraphEdge> edges;   // undirected: one edge per pair, usable both ways
};

struct GraphOptions
{
  double nominal_speed = 0.5;     // [m/s] for Euclidean costs
  double gateway_crossing_time = 2.0;  // [s] before a gateway's time has been learned
};

RgGraph build_graph(const RgMap& map, const GraphOptions& options = {});

// Cheapest path between two nodes (Dijkstra; the graph is small). Empty if unreachable.
std::vector<int64_t> shortest_path(const RgGraph& graph, int64_t from_node, int64_t to_node);

}  // namespace rgnav::rgmap
