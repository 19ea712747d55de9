// Why a region's precision (rgmap_metrics.h: the share of its freespace in its best room) falls
// short: each of its cells outside the best room lies either in a room where the region's own
// robot stood (the robot drove through a doorway the region did not end at: a missed gateway,
// or a merge of two rooms) or in a room it never stood in (space seen through an opening and
// not clipped there). Unweighted over regions like the precision, so the two losses add up to
// 1 - precision exactly.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "rgmap_metrics.h"

namespace rgnav::rgmap_pipeline {

struct RegionDiagnosis
{
  int64_t region = 0;
  int64_t cells = 0;                          // freespace cells inside rooms
  int32_t best_room = 0;
  int64_t best_cells = 0;
  int64_t seen_cells = 0;                     // in other rooms, none of the region's robot positions in them
  int64_t driven_cells = 0;                   // in other rooms the region's robot stood in
  std::map<int32_t, int64_t> room_cells;      // room -> cells
  std::map<int32_t, int> room_positions;      // room -> robot positions (0: outside every room)
  // The rooms of the robot positions in the order given (time order), runs of one room as
  // (room, positions): 3 in the hallway, 75 in a room, 119 in the hallway again is a room left
  // without a gateway (office_g, before RG kernel door_exits).
  std::vector<std::pair<int32_t, int>> path;
};

struct SegmentationDiagnosis
{
  std::vector<RegionDiagnosis> regions;       // regions with a cell in a room
  double seen_loss = 0;                       // mean over regions of seen_cells / cells
  double driven_loss = 0;                     // mean over regions of driven_cells / cells
};

// positions: robot positions of each region in the label grid's (world) frame. A position on a
// wall or door cell (label 0) counts for the nearest room within 0.3 m.
SegmentationDiagnosis diagnose_segmentation(const LabelGrid& truth, const RegionCells& found,
                                            const std::map<int64_t, std::vector<Eigen::Vector2d>>& positions);

// One line per region: cells, best room and share, the other rooms' cells (marked * where the
// robot stood), the robot's positions per room and its path, for the bench's --diagnose.
std::string to_text(const SegmentationDiagnosis& d, const std::vector<std::string>& room_names);

}  // namespace rgnav::rgmap_pipeline
