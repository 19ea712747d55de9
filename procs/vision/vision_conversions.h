// ObstacleGrid <-> obstacle_grid_t (OBSTACLES_3D); a frame's rectangles -> objects3d_t (OBJECTS_3D).
#pragma once

#include <vector>

#include "geometry/pose2.h"
#include "rgnav/objects3d_t.hpp"
#include "rgnav/obstacle_grid_t.hpp"
#include "vision/object_rectangles.h"
#include "vision/obstacle_map.h"

namespace rgnav::vision {

obstacle_grid_t to_msg(const ObstacleGrid& g);
ObstacleGrid from_msg(const obstacle_grid_t& m);
// Rectangles of one frame (base frame at capture) with the robot's pose then and the newest laser
// scan's id (consumers re-anchor them by it, diss. 3.3.5). Ids number them within the frame
// (no tracking across frames: the RG kernel merges repeated observations).
objects3d_t to_msg(const std::vector<ObjectRectangle>& rectangles, int64_t utime, int64_t frame_id, int64_t scan_id,
                   const geometry::Pose2& odom_from_base);

}  // namespace rgnav::vision
