// Laser-based detection of narrow passages (diss. 4.2.1): the closest points left and right of
// the viewing direction, their distance D_lr, the aperture angle alpha_NP and the distance D_NP
// to where their connecting line crosses the line of sight; the thresholds D_NP^max, D_lr^min
// (twice robot radius plus safety) and the door-width/aperture ranges; the walk from each
// gateway point toward the other that checks for free space behind the passage and yields
// further candidates; finally the candidate pair of minimum distance. Laser frame throughout.
#pragma once

#include <optional>
#include <vector>

#include "gateway_detector/features.h"
#include "gateway_detector/scan.h"

namespace rgnav::gateway_detector {

struct NarrowPassageOptions
{
  std::vector<double> viewing_directions{0.0};  // [rad] alpha_m in the laser frame, one search each
  double half_range = 0.7;         // [rad] Delta alpha: the left range is (alpha_m, alpha_m + Delta alpha); narrow
                                   // enough that the side walls of a corridor leading to a door are not the closest points
  double max_distance = 2.5;       // [m] D_NP^max
  double robot_radius = 0.26;      // [m]
  double safety_distance = 0.09;   // [m] D_lr^min = 2 (radius + safety)
  double min_width = 0.70;         // [m] door-width range (laser only)
  double max_width = 1.30;         // [m]
  double min_aperture = 0.25;      // [rad] alpha_NP range
  double max_aperture = 3.0;       // [rad]
  double min_depth_behind = 0.5;   // [m] a gap behind the passage must reach at least this far past it
  // A gateway point of a door is the end of a wall, a jamb or a door leaf; the legs of tables
  // and chairs (a few centimetres of surface with free space around) make passages a robot
  // cannot take and no door. Each gateway point's surface (the run of hits through it, each
  // within jamb_link_distance of the next) must extend at least this far; 0 disables the check.
  double min_jamb_extent = 0.0;    // [m]
  double jamb_link_distance = 0.15;  // [m]
  // Openings in a wall seen from the side (the robot drives along a wall and turns into a door
  // at the last moment, when its jambs are already out of a forward view): a gap of door width
  // between two segments of one virtual line, with the beams through it passing the line.
  bool wall_gaps = true;
  double wall_gap_max_distance = 3.0;  // [m] from the laser to the gap's middle
  double wall_gap_min_through = 0.8;   // fraction of the beams in the gap that must pass the line

  double min_passage_width() const { return 2.0 * (robot_radius + safety_distance); }  // D_lr^min
};

struct NarrowPassage
{
  Vec2 left;             // gateway points (laser frame)
  Vec2 right;
  size_t left_index = 0;
  size_t right_index = 0;
  double width = 0.0;    // D_lr
  double distance = 0.0; // D_NP
  double aperture = 0.0; // alpha_NP
  double viewing_direction = 0.0;
  Vec2 midpoint() const { return 0.5 * (left + right); }
};

// The steps of 4.2.1 for one viewing direction, exposed for tests.
struct ClosestPair
{
  size_t left = 0, right = 0;
  double d_lr = 0.0, d_np = 0.0, aperture = 0.0;
};
std::optional<ClosestPair> closest_pair(const sensors::LaserScan& scan, double viewing_direction, double half_range);
// Walks from beam `from` toward beam `to` while consecutive points are closer than D_lr^min and
// the opposite gateway point is still further than D_lr^min. Returns the beam at the edge of the
// first gap (a new candidate gateway point), or nullopt if no free space opens up.
std::optional<size_t> walk_to_gap(const sensors::LaserScan& scan, size_t from, size_t to, const NarrowPassageOptions& o);

std::vector<NarrowPassage> detect_narrow_passages(const sensors::LaserScan& scan, const NarrowPassageOptions& options);
// Extent [m] of the surface through beam i: the distance between the ends of the run of hits
// around it in which each hit lies within link_distance of the next.
double surface_extent(const sensors::LaserScan& scan, size_t i, double link_distance);
// Door-width gaps in the virtual lines of the scan (see wall_gaps above).
std::vector<NarrowPassage> detect_wall_gaps(const sensors::LaserScan& scan, const ScanFeatures& features, const NarrowPassageOptions& options);

}  // namespace rgnav::gateway_detector
