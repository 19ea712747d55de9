// The detour finder behind the chain planner: when none of the chain planner's candidates
// (direct clothoids, Dubins, detours through one lateral via-pose) is free, e.g. behind a
// box in front of the target or in front of a door seen at an angle, an A* search on a
// local grid finds the way around, and the chain planner then builds primitives along it.
// The grid is the local map rasterised around the robot and the target; a cell is passable
// when its distance to the nearest obstacle (OpenCV's exact Euclidean distance transform)
// is at least the required clearance and some kept scan saw it (free, or in the shadow of
// an obstacle at a higher cost; never outside every field of view); cells close to
// obstacles cost more, so the path keeps to the middle.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "collision_avoidance/local_map.h"

namespace rgnav::collision_avoidance {

struct GridPathOptions
{
  double cell = 0.05;        // [m] grid pitch
  double margin = 2.0;       // [m] the grid extends this far beyond robot and target
  double max_extent = 16.0;  // [m] longest grid side
  double comfort = 0.4;      // [m] extra clearance beyond which a cell costs nothing more
  double comfort_weight = 2.0;  // cost factor of cells within `comfort` of the required clearance
  double shadow_cost = 3.0;     // cost factor of cells in the field of view but not seen (behind obstacles)
};

// Waypoints from `from` (excluded) to `to` (included), odom frame, reduced to the corners of
// a line-of-sight simplified path whose every straight leg keeps `clearance` from the map's
// points (checked on the exact points, not the grid); nothing if no path exists. A start
// cell inside the clearance (the robot already close to something) is allowed: the search
// may leave it toward increasing clearance.
std::optional<std::vector<Eigen::Vector2d>> grid_path(const LocalMap& map, const Eigen::Vector2d& from,
                                                      const Eigen::Vector2d& to, double clearance,
                                                      const GridPathOptions& options);

}  // namespace rgnav::collision_avoidance
