// Whether a line the robot crossed is a narrowing of the free space: the one principled test a
// new line gateway (the detector's door or narrow passage, a doorway of the line map, a step into
// a known place) must pass before it splits a region. A gateway is a local minimum of the free
// space's width along the robot's way through it, significantly narrower than the space on both
// sides (the critical lines of Thrun 1998's Voronoi-based topological maps; Bormann et al. 2016's
// Voronoi segmentation cuts at the same minima). A stretch of hallway as narrow as a door (1.2 m
// hallways, door-wide 0.7-1.5 m) is no such minimum: the hallway is as narrow before and after.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct NarrowingOptions
{
  // A line is a narrowing if its width is at most this share of the free width on each side
  // (0: every line is). 0.8: the narrowing takes at least a fifth of the width away; a door
  // (<= 1.5 m) from a hallway into a room has the hallway's length on one side and the room on
  // the other, a cut across a hallway the same width on both.
  double max_width_ratio = 0.8;
  // [m] The free width on a side is measured across the way (parallel to the line) at probes
  // 0.4 m (past a wall's thickness and the jambs) to this far from the line, as far as the way
  // is free; their median, so that a chair's legs or a gap beside a probe or two do not decide it.
  double probe_depth = 1.4;
  double cap = 6.0;   // [m] widths are measured up to this (a ray that meets no wall)
};

// The free widths about a crossed line (width, and on each side: NaN if no probe fits).
struct NarrowingProfile
{
  double width = 0.0;     // [m] |p - q|
  double before = 0.0;    // [m] on the side the crossing came from
  double after = 0.0;     // [m] on the side it went to
  bool narrowing = true;
};

// The profile of the line p-q crossed with `heading` (unit), all in one frame with `walls` (the
// region's line map: rays end at its segments).
NarrowingProfile narrowing_profile(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& heading,
                                   const std::vector<rgmap::LineSegment>& walls, const NarrowingOptions& options);

}  // namespace rgnav::rg_kernel
