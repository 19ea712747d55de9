// How much a look past a frontier can still show (diss. 4.2.1: whether a passage offers new
// views; the information gain of next-best-view exploration, González-Baños and Latombe 2002):
// the unknown area in a fan of rays from the frontier outward, each ray cut at the first line of
// any region's map (a wall hides what lies behind it), a place unknown when no live region of
// the map has it as free. A frontier whose fan the map already knows (free space another region
// holds beyond a gap of a cell or two, a corner behind furniture the robot saw from elsewhere, a
// freespace edge the line map closes a little farther on) offers nothing to go and look at.
// Off by default (ExplorerOptions: min_m2 0): measured, it sped the coverage up but the robot
// entered fewer rooms (the first target); see config/explorer.yaml.
#pragma once

#include <Eigen/Core>

#include "explorer/explorer_options.h"
#include "rgmap/rg_map.h"

namespace rgnav::explorer {

// [m^2] Unknown area seen from `from` (map frame) over `outward` +- o.fan_rad out to o.range_m:
// each ray stops at the first line of a live region it crosses.
double unknown_area_beyond(const rgmap::RgMap& map, const Eigen::Vector2d& from, const Eigen::Vector2d& outward,
                           const GainOptions& o);

}  // namespace rgnav::explorer
