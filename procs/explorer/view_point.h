// Where the robot goes to look at a frontier (ch. 7 exploration; what Yamauchi's frontier
// explorers do with "the nearest reachable cell"): a frontier cell itself lies on the edge of the
// region's freespace, where the robot's body does not fit (the planner's grid blocks a radius
// round everything it does not know), or in a scrap of free space the robot cannot drive to
// (behind a table, past a gap narrower than the robot). A goal there is one the planner cannot
// reach or one the robot presses against the unknown to get near. The view point is a cell of
// the planner's own grid of the region (planner/region_grid.h) where the robot fits, in a piece
// of free space it can drive to, within range of the frontier with nothing of the region's line
// map between; the nearest such cell, a shortfall of clearance below radius + margin counting
// as extra distance, so that the robot looks from open space where there is some. No such cell:
// nothing to drive to for now (the map changes as the robot sees more).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <vector>

#include "explorer/explorer_options.h"
#include "planner/region_planner.h"

namespace rgnav::explorer {

struct ViewPoint
{
  Eigen::Vector2d point{0, 0};   // [m] region frame: a free cell's centre
  double heading = 0;            // [rad] region frame: facing the frontier (along `outward` when on it)
};

// The view point of the frontier point `target` (region frame; `outward`: from the free side into
// the unknown) on `grid`, among the free cells
// of the pieces `pieces` (RegionGrid::component ids), with `walls` the region's line map
// (region frame). wanted_clearance [m]: the clearance the robot would like round it.
std::optional<ViewPoint> view_point(const planner::RegionGrid& grid, const std::vector<int32_t>& pieces,
                                    const Eigen::Vector2d& target, const Eigen::Vector2d& outward,
                                    const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& walls,
                                    double wanted_clearance, const ViewOptions& options);

}  // namespace rgnav::explorer
