// Evaluation of RG maps against ground truth (./rgnav bench rgmap), plain geometry and graphs:
//  - segmentation: the map's regions (freespace cells) against the ground-truth rooms of a label
//    grid, after Bormann et al. 2016 as their evaluation code computes the paper's figures
//    (ipa_room_segmentation, EvaluationSegmentation::computePrecisionRecall, the "micro" values):
//    precision = per region, the share of its cells that lie in its best-overlapping room;
//    recall = per room, the share of its cells covered by its best-overlapping region; both
//    averaged unweighted (each region / room counts once, whatever its size). Segments and rooms
//    of at most 100 pixels (0.25 m^2 at the maps' 0.05 m) are left out there, as here
//    (kMinSegmentArea). Recall is taken over the cells of the room that some region covers (what
//    the robot explored) and, separately, over all its cells (recall_full: the paper's, whose
//    segmentations cover the whole map). Two differences remain, both from an RG map being no
//    partition: regions overlap (a cell seen from two regions counts in both), and a region's
//    cells outside every room (walls, door-closing lines of the ground truth) are left out of
//    its size, where the paper's segment size counts every pixel of the segment.
//  - gateways: gateway positions matched one-to-one to ground-truth gateways, nearest pairs first.
//  - graphs: the region adjacency graph against the ground-truth room graph, by isomorphism and,
//    through the region -> best room correspondence, edge by edge.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::rgmap_pipeline {

// A grid of labels in the world frame: cell (cx, cy) covers origin + [cx, cx+1) x [cy, cy+1)
// times resolution; label 0 = no room (walls, outside).
struct LabelGrid
{
  int width = 0, height = 0;
  double resolution = 0.05;                 // [m]
  Eigen::Vector2d origin{0, 0};             // [m] world position of cell (0, 0)'s lower-left corner
  std::vector<int32_t> labels;              // row-major, y up: index = cy * width + cx

  LabelGrid() = default;
  LabelGrid(int w, int h, double res, Eigen::Vector2d org) : width(w), height(h), resolution(res), origin(org), labels(static_cast<size_t>(w) * h, 0) {}
  int32_t& at(int cx, int cy) { return labels[static_cast<size_t>(cy) * width + cx]; }
  int32_t at(int cx, int cy) const { return labels[static_cast<size_t>(cy) * width + cx]; }
  Eigen::Vector2d center(int cx, int cy) const { return origin + resolution * Eigen::Vector2d(cx + 0.5, cy + 0.5); }
};

// Cells (indices into a LabelGrid) covered by each found region; regions may overlap.
using RegionCells = std::map<int64_t, std::vector<int64_t>>;

struct SegmentationScore
{
  double precision = 0;        // mean over regions inside labelled space
  double recall = 0;           // mean over explored rooms, of the explored part
  double recall_full = 0;      // mean over all rooms, of the whole room (unexplored counts as missed)
  double jaccard = 0;          // mean over explored rooms of the best region's IoU (explored cells)
  double coverage = 0;         // share of labelled cells covered by some region
  int rooms = 0;               // labels present in the grid
  int rooms_explored = 0;      // ... with a covered cell
  int regions = 0;             // regions given
  int regions_outside = 0;     // regions with no cell in a room
  int over_segmented = 0;      // rooms split by >= 2 regions each covering >= split_share of it
  int under_segmented = 0;     // regions spanning >= 2 rooms each >= split_share of the region
  std::map<int64_t, int32_t> region_to_room;  // best-overlapping room of each region
};

// [m^2] Bormann et al.'s evaluation leaves out segments and rooms of <= 100 pixels at 0.05 m.
constexpr double kMinSegmentArea = 0.25;
// Cells of kMinSegmentArea in `grid` (at least 1).
int64_t min_segment_cells(const LabelGrid& grid);

// Regions of `found` with more than min_cells cells.
RegionCells without_small_regions(const RegionCells& found, int64_t min_cells);

// The grid with rooms of at most min_cells cells unlabelled (0).
LabelGrid without_small_rooms(LabelGrid grid, int64_t min_cells);

SegmentationScore score_segmentation(const LabelGrid& truth, const RegionCells& found, double split_share = 0.2);

struct GatewayMatch
{
  int truth = 0, found = 0, matched = 0, missed = 0, false_positives = 0;
  double mean_error_m = 0;                   // over matched pairs
  std::vector<std::pair<int, int>> pairs;    // (truth index, found index)
};

// One-to-one, nearest pairs first (ties: lower indices first), within max_distance.
GatewayMatch match_gateways(const std::vector<Eigen::Vector2d>& truth, const std::vector<Eigen::Vector2d>& found,
                            double max_distance);

// Simple undirected graph: no self loops, no parallel edges (edges stored with first < second).
struct Graph
{
  std::set<int64_t> nodes;
  std::set<std::pair<int64_t, int64_t>> edges;
  void add_edge(int64_t a, int64_t b);   // ignores a == b; adds missing nodes
};

// Exact isomorphism test (colour refinement, then backtracking over same-colour candidates).
bool isomorphic(const Graph& a, const Graph& b);

struct GraphComparison
{
  bool isomorphic = false;
  int truth_nodes = 0, map_nodes = 0, truth_edges = 0, map_edges = 0;
  int edges_matched = 0;     // truth edges that some map edge maps onto
  int edges_missing = 0;     // truth edges no map edge maps onto
  int edges_extra = 0;       // map edges between regions of two rooms that are not adjacent
  int edges_internal = 0;    // map edges between two regions of the same room
  int rooms_unmatched = 0;   // truth nodes no region maps onto
};

// map_to_truth: region -> room (regions missing from it are unmatched and their edges extra).
GraphComparison compare_graphs(const Graph& truth, const Graph& map, const std::map<int64_t, int64_t>& map_to_truth);

// The region graph of an RG map: live (not merged) regions; an edge per pair of regions joined
// by a gateway that is traversed (both sides known) and not neutralized. A crossing joins every
// pair of the regions its gateways join (see repeated_crossings), as the truth's crossings do.
Graph region_graph(const rgmap::RgMap& map);

// A crossing joining more than two regions is one gateway per pair of them in an RG map (a
// gateway has two sides), all with the crossing's outline: the ids of those repeating the
// outline of a lower-id gateway (within 1 cm). One gateway for counting and matching.
std::set<int64_t> repeated_crossings(const rgmap::RgMap& map);

// Table 6.1 of the dissertation plus structure and compactness; a crossing counts once.
struct MapCounts
{
  int regions = 0;             // live
  int merged = 0;              // regions merged into others (loops closed / missed gateways)
  int gateways = 0;            // not neutralized
  int doors = 0;               // ... of class door or narrow passage
  int neutralized = 0;
  int not_traversed = 0;       // gateways with only one side known
  int segments = 0;
  int64_t scan_points = 0;     // raw end points stacked into regions
  double compression = 0;      // scan_points / segment end points
  double mean_region_bytes = 0;  // freespace bitmap + segments (4 float coordinates) per region
  double mean_region_area_m2 = 0;
  int consistency_problems = 0;
  int overlapping_regions = 0;  // overlapping_region_pairs: one place mapped twice
};
MapCounts count_map(const rgmap::RgMap& map, int64_t scan_points);

// Pairs of live regions of which the smaller one has at least `share` of its freespace (cells of
// a map-frame grid) inside the other's: one place mapped as two regions (a false gateway whose
// region was not merged back, a loop not closed). consistency_problems cannot see these. A
// region's view through an opening into its neighbour overlaps that neighbour, but not by half.
int overlapping_region_pairs(const rgmap::RgMap& map, double share = 0.5, double resolution = 0.15);

// Cells of a LabelGrid inside each live region's freespace, the region placed by
// world_from_map * map_from_region.
RegionCells region_cells(const rgmap::RgMap& map, const geometry::Pose2& world_from_map, const LabelGrid& grid);

// Least-squares rigid transform b_from_a with b[i] ~ b_from_a * a[i] (at least 2 points).
geometry::Pose2 fit_rigid(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b);

// Gateway positions of an RG map (mean of the gateway points, else the crossing points) in the
// map frame, for the gateways count_map counts (not neutralized, a crossing once).
std::vector<Eigen::Vector2d> gateway_positions(const rgmap::RgMap& map);

}  // namespace rgnav::rgmap_pipeline
