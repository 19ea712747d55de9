// Doorways of a region's own line map: gaps of door width in a straight wall (two collinear
// wall segments whose facing ends are 0.6-1.5 m apart). Through such a gap the region's robot
// sees the room behind it; until that door is crossed (and becomes a gateway) nothing but the
// line map tells the kernel that the space behind belongs to another room. A region whose robot
// never went through a doorway ends there, like at a gateway (diss. 5.2 filters the beams that
// cross a gateway); a doorway the robot did go through is a gateway the detector missed, and
// the region keeps both sides.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "procs/rg_kernel/gateway_geometry.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct DoorwayOptions
{
  bool enabled = true;
  double min_width = 0.6;          // [m] narrower gaps: missing wall points, not a door
  double max_width = 1.5;          // [m] wider: an opening between regions the detector classifies
  double min_wall_length = 0.3;    // [m] each wall piece beside the gap at least this long
  double max_angle = 0.1745;       // [rad] wall pieces and gap line this parallel (10 deg) ...
  double max_offset = 0.10;        // [m] ... and the gap ends this near the other piece's line
};

// The gap lines (facing ends of two collinear wall segments), in the segments' frame.
std::vector<Line> find_doorways(const std::vector<rgmap::LineSegment>& segments, const DoorwayOptions& options);

// The doorway of the line map (segments near the step suffice) that the robot's step from `from`
// to `to` goes through, if any; a step longer than a door is wide is a jump, not a step.
std::optional<Line> doorway_stepped_through(const std::vector<rgmap::LineSegment>& segments, const Eigen::Vector2d& from,
                                            const Eigen::Vector2d& to, const DoorwayOptions& options);

// The doorways no step of the robot's path (positions in time order) goes through.
std::vector<Line> doorways_not_crossed(const std::vector<Line>& doorways, const std::vector<Eigen::Vector2d>& path);

}  // namespace rgnav::rg_kernel
