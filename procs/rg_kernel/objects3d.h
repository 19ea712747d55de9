// 3D objects of a region (diss. 3.3.5, Table 2.1): rectangles the vision reconstructed from
// stereo (doors, whiteboards, monitors, table tops), re-anchored by the node to the map frame
// through the scan mapper's correction of the scan taken at capture (the scan id), kept in the
// frame of the region the robot was in. The same object seen again (near centre, parallel
// plane, similar size) is one object: its corners become the average of its observations and
// its confidence grows with their number; others are new objects.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct Objects3dOptions
{
  bool enabled = true;
  double match_distance = 0.30;   // [m] centres of one object's observations at most this apart
  double match_angle_deg = 20.0;  // their planes at most this far from parallel (either facing)
  double match_size_ratio = 0.3;  // their sides differ by at most this share
  int max_per_region = 100;       // the most observed are kept
};

// Observed rectangles (map frame) into the region frame of `map_from_region`: corners and
// normal turned and moved in the plane, heights kept.
std::vector<rgmap::Rectangle3d> to_region_frame(const std::vector<rgmap::Rectangle3d>& in_map,
                                                const geometry::Pose2& map_from_region);

// Merges `observed` (region frame) into `objects`; new objects take ids from *next_id.
void merge_objects3d(std::vector<rgmap::Rectangle3d>* objects, const std::vector<rgmap::Rectangle3d>& observed,
                     int64_t* next_id, const Objects3dOptions& options);

}  // namespace rgnav::rg_kernel
