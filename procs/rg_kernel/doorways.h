// Doorways of a region's own line map: gaps of door width in a straight wall (two collinear
// wall segments whose facing ends are 0.6-1.5 m apart), and, if asked for, the gap between a
// wall's free end and the wall its line runs into (a wall that stops short of a crossing wall
// or a corner: a room divided by a partition, an opening beside a corner). Through such a gap
// the region's robot sees the room behind it; until that door is crossed (and becomes a
// gateway) nothing but the line map tells the kernel that the space behind belongs to another
// room. A region whose robot never went through a doorway ends there, like at a gateway (diss.
// 5.2 filters the beams that cross a gateway); a doorway the robot did go through is a gateway
// the detector missed, and the region keeps both sides.
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
  // Wall-end gaps: from the free end of a wall at least wall_end_min_wall_length long, along its
  // line, to the first wall it runs into at wall_end_min_angle or more, min_width to
  // wall_end_max_width away. Building plans divide rooms there: a wide opening beside the end of
  // a partition that stops short, rooms open onto a hallway between their partitions; the
  // collinear rule sees neither. The wall must be long: the short
  // faces of door frames, extended across a hallway, would cut it at every door. 0: off.
  double wall_end_max_width = 0.0;        // [m]
  double wall_end_min_wall_length = 1.0;  // [m]
  double wall_end_min_angle = 0.7854;     // [rad] (45 deg) not along the wall: across it
  double wall_end_free_radius = 0.3;      // [m] an end with a crossing wall this near is a corner, not free
  double wall_end_corner_tolerance = 0.3; // [m] the line may run into the wall this far past its end (a corner)
  // An end in line with another wall across it (that wall's line this near the end, its nearer
  // end at most max_width away) is a jamb of an opening in that wall's line: the opening lies
  // along that line, not along the wall's (partitions between rooms that open onto a hallway end
  // flush with the rooms' front walls, and their lines run on across the hallway).
  double wall_end_in_line_offset = 0.3;   // [m]
};

// The gap lines (facing ends of two collinear wall segments, then wall-end gaps), in the
// segments' frame.
std::vector<Line> find_doorways(const std::vector<rgmap::LineSegment>& segments, const DoorwayOptions& options);

// The doorway of the line map (segments near the step suffice) that the robot's step from `from`
// to `to` goes through, if any; a step longer than a door is wide is a jump, not a step.
std::optional<Line> doorway_stepped_through(const std::vector<rgmap::LineSegment>& segments, const Eigen::Vector2d& from,
                                            const Eigen::Vector2d& to, const DoorwayOptions& options);

// The doorways no step of the robot's path (positions in time order) goes through.
std::vector<Line> doorways_not_crossed(const std::vector<Line>& doorways, const std::vector<Eigen::Vector2d>& path);

}  // namespace rgnav::rg_kernel
