// Line-map segments with nothing static of the world behind them (issue 33: only the static
// structure in the map). A walking person's legs, seen for a few scans and merged into a region's
// line map, leave short segments across hallways that a planner or a localizer takes for walls.
//
// Judged against the world's static surfaces at the laser's height (sim::Scene: walls, every
// door leaf whether open or closed, boxes, table legs; people are no part of it), in the world
// frame (the map placed by the run's rigid fit): a segment is a ghost when more than half of its
// length lies farther than `tolerance` (0.1 m) from every static surface. Its length rather than
// its midpoint or one end: a wall segment running a little past a door jamb, or a leg segment
// that touches a wall at one end, is judged by where most of it lies. Sampled every 2 cm.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"
#include "sim/scene.h"
#include "sim/world.h"

namespace rgnav::rgmap_pipeline {

struct GhostSegments
{
  int segments = 0;            // of the live regions (as MapCounts::segments)
  int ghosts = 0;
  double ghost_length_m = 0;
  // World frame, for pictures and diagnosis.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> ghost_list;
};

class StaticSurfaces
{
 public:
  // scan_height: the laser's scan plane above the floor [m].
  StaticSurfaces(const sim::World& world, double scan_height);
  // Share of the segment a-b (world frame) farther than `tolerance` from every static surface.
  double share_away(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double tolerance) const;

 private:
  sim::Scene scene_;
  std::vector<uint8_t> doors_closed_;
  double scan_height_;
};

GhostSegments count_ghost_segments(const rgmap::RgMap& map, const geometry::Pose2& world_from_map,
                                   const StaticSurfaces& statics, double tolerance = 0.1);

}  // namespace rgnav::rgmap_pipeline
