// Frontiers of a region (diss. 2.1.1 completeness, ch. 7 exploration): where the region's
// freespace bitmap ends in space that is unknown in the whole map. An edge cell of the freespace
// (a free cell with a non-free 4-neighbour) is explained when a line of the region's map lies
// across the way out through the neighbour, up to wall_distance past it (a wall; one beside the
// way, as a door's jamb beside its opening, is not), when the neighbour is free in another region
// (the map knows it from there), or when a traversed door-like gateway's line lies within
// gateway_distance (its opening: the kernel ends both sides' freespace short of it; a crossing's
// outline explains nothing, its other branches may lead anywhere); the rest are frontier cells, grouped 8-connected into frontiers. A frontier narrower
// than min_width is a shadow (behind a table leg) and no goal.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "explorer/explorer_options.h"
#include "rgmap/rg_map.h"

namespace rgnav::explorer {

struct Frontier
{
  int64_t region_id = 0;
  std::vector<Eigen::Vector2d> cells;   // [m] region frame, centres of the free edge cells
  Eigen::Vector2d centroid{0, 0};       // [m] region frame
  Eigen::Vector2d goal{0, 0};           // [m] region frame: the frontier cell nearest its centroid
  Eigen::Vector2d outward{1, 0};        // region frame unit vector: from the free side into the unknown
  double width = 0;                     // [m] largest extent of its cells
};

struct RegionFrontiers
{
  std::vector<Frontier> frontiers;      // min_width or wider, widest first
  int edge_cells = 0;                   // freespace edge cells
  int frontier_cells = 0;               // ... not explained (shadows included)
  // 1 - frontier_cells / edge_cells: the share of the region's freespace edge that is explained
  // (diss. 2.1.1's completeness, measured on the edge rather than on the bounding box).
  double completeness() const { return edge_cells > 0 ? 1.0 - static_cast<double>(frontier_cells) / edge_cells : 0.0; }
};

// Frontiers of live region `region_id` of `map` (empty for a merged or unknown region).
RegionFrontiers find_frontiers(const rgmap::RgMap& map, int64_t region_id, const FrontierOptions& options);

// True if the map-frame point lies in free space of any live region of `map`; `settled_only`:
// of a region the robot has left (finalised). The open region's freespace is provisional: it
// takes in all the laser saw from it, the branches of a crossing not gone through too, and ends
// at that crossing once the region is finalised.
bool known_free(const rgmap::RgMap& map, const Eigen::Vector2d& map_point, bool settled_only = false);

}  // namespace rgnav::explorer
