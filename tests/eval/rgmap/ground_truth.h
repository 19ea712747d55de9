// Ground truth of a simulated world for RG map evaluation: the rooms as a label grid, the
// gateways between them, and the room adjacency graph. World files (config/worlds) label rooms
// and gateways; the IPA building maps label rooms only (sim::load_world reads them from
// <map>_gt_segmentation.png, where black lines close the doorways): there a gateway is each
// connected run of doorway pixels — free in the map, closed in the segmentation — touching two rooms.
#pragma once

#include <string>
#include <vector>

#include "rgmap_metrics.h"
#include "sim/world.h"

namespace rgnav::rgmap_pipeline {

struct TruthGateway
{
  std::string name;
  // [m] world frame: the gateway line (2 points) or the outline of a crossing (4 points,
  // dissertation fig. 4.1); the robot went through it when its path crosses an edge.
  std::vector<Eigen::Vector2d> points;
  // Labels of the rooms it joins: those the world names (from, to, joins: office.yaml's X-crossing
  // joins four hallways), and the room its centre lies in if that is another. Dead ends: one.
  std::vector<int32_t> rooms;
  Eigen::Vector2d center() const;
};

struct GroundTruth
{
  LabelGrid rooms;                     // label k = world.regions[k - 1]
  std::vector<std::string> room_names; // index label - 1
  std::vector<TruthGateway> gateways;
  int32_t label_of(const std::string& room) const;   // 0 if unknown
};

GroundTruth ground_truth_of(const sim::World& world, double resolution = 0.05);

// Doorway runs of an IPA map (free >250 in the map image, not free in the segmentation image);
// rooms from `rooms`. Exposed for tests.
std::vector<TruthGateway> gateways_from_images(const std::string& map_png, const std::string& segmentation_png,
                                               double resolution, const LabelGrid& rooms);

// The room graph: the given rooms (labels), an edge per pair joined by a gateway.
Graph truth_graph(const GroundTruth& truth, const std::vector<int32_t>& rooms);

// Gateways whose line the polyline crosses (the robot went through them).
std::vector<int> crossed_gateways(const GroundTruth& truth, const std::vector<Eigen::Vector2d>& path);

}  // namespace rgnav::rgmap_pipeline
