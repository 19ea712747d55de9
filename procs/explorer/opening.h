// Where a stacked gateway's goal goes through. The gateway detector estimates a door it sees from
// a hallway from the side, and a hallway's crossing of a door lies on the hallway's middle: its
// crossing point is often most of a metre along the wall from the opening. A goal beyond_m past
// that point lies in the wall or against a jamb, and the robot drives at the wall until the goal
// fails for no progress. The map's lines show where the opening is: the goal is aimed through the
// nearest place beside the crossing where a lane as wide as the robot runs through no line.
#pragma once

#include <Eigen/Core>

#include <optional>

#include "rgmap/rg_map.h"

namespace rgnav::explorer {

struct OpeningOptions
{
  double search_m = 1.0;   // [m] the opening is looked for this far to either side of the crossing (0: off)
  double step_m = 0.05;    // [m] lanes this far apart
  double back_m = 0.3;     // [m] a lane begins this far before the crossing point (on the known side)
  double wall_pass_m = 0.3;  // [m] a lane through the opening meets nothing this far past the wall's line
};

// `crossing` moved sideways (across `heading`, map frame) to the nearest place within search_m
// where a lane `width` wide, from back_m before it toward `depth` past it, passes the wall the
// gateway is in (the line most straight ways from the crossing meet first) by wall_pass_m
// before it meets any line of a live region of `map` (map frame); `crossing` itself when its own
// lane does, when no line is met (nothing known to aim by) or when the search is off. Nothing
// when lines are met and every place within search_m is too narrow for the lane: the map shows
// no opening the robot fits through there (a gap between furniture, a corner or a wall taken for
// a door).
std::optional<Eigen::Vector2d> aim_through_opening(const rgmap::RgMap& map, const Eigen::Vector2d& crossing, double heading,
                                                   double depth, double width, const OpeningOptions& options);

}  // namespace rgnav::explorer
