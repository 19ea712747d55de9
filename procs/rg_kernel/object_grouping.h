// 2D objects of a region from its line map and its scans (diss. 3.1, 3.2; Table 2.1 lists
// "2D rectangles, 2D circle" among a region's object hypotheses).
//
// Rectangles: the two-stage line grouping of diss. 3.1 (Fig. 3.2) in its restrictive form
// with the parameters of 3.2: first every pair of merged segments whose lines meet at
// alpha_min..alpha_max with a gap below DN_max is a "corner"; then pairs of corners that
// close a cycle of four sides (each side a direct neighbour of both of its neighbours — the
// restrictive AND — and opposite sides more than DO_min apart) are rectangles. Because a
// laser sees a box from the side the robot drove on, a box against a wall shows three sides
// and a box in a corner or seen from one side two: those are completed to rectangles too
// (three sides: the hidden side at the far ends of the two parallel sides; two sides: the
// rectangle the two sides span), with smaller confidence. The dissertation keeps all
// hypotheses and then deletes those "contained in others or strongly overlapping"; we do the
// same, preferring hypotheses with more observed sides.
// The dissertation does not say how walls are kept out; a room's outline groups into
// rectangles just as well. We use the region's freespace: an object is something the robot
// saw from outside — the cells just outside every observed side are free and the inside is
// not — whereas walls are seen from inside the rectangle they form (inside free, outside not).
//
// Circles: the dissertation names circles as object hypotheses but does not describe how it
// finds them. Here they are fitted to short arcs of scan points: in every scan, a short run
// of points standing in front of its neighbours (a free-standing thing, e.g. a pillar) that a
// circle fits much better than a line, convex towards the laser, is one observation; the
// observations of the region's scans are clustered, and a cluster seen in enough scans whose
// centre is not free space is a circle.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "geometry/pose2.h"
#include "rgmap/freespace_bitmap.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct ObjectOptions
{
  bool enabled = true;
  // Line grouping, restrictive case (diss. 3.2).
  double alpha_min = 80.0 * M_PI / 180.0;   // [rad] angle between neighbouring sides
  double alpha_max = 100.0 * M_PI / 180.0;  // [rad]
  double dn_max = 0.20;                     // [m] DN_max: gap between neighbouring sides
  double do_min = 0.20;                     // [m] DO_min: distance between opposite sides (minimum size)
  double max_side = 3.0;                    // [m] longer rectangles are structure, not objects
  double max_side_from_two = 1.5;           // [m] two-sided hypotheses: both sides at most this long
  bool complete_three_sides = true;
  bool complete_two_sides = true;
  int64_t max_hypotheses = 20000;           // side groups examined per region at most
  // Telling objects from walls by the freespace.
  double outside_offset = 0.20;             // [m] probes this far outside each observed side
  double min_outside_free = 0.5;            // share of probes outside an observed side that are free
  double max_inside_free = 0.2;             // share of the inside that may be free
  // Circles from arcs of scan points.
  bool circles = true;
  double arc_point_gap = 0.10;              // [m] consecutive points farther apart end an arc
  int arc_min_points = 5;
  double circle_min_radius = 0.05;          // [m]
  double circle_max_radius = 0.40;          // [m]
  double circle_max_rms = 0.012;            // [m] residual of the circle fit
  double arc_depth_jump = 0.20;             // [m] the arc stands at least this much in front of its neighbours
  int circle_min_scans = 3;                 // observations needed for a circle
};

// One region's input: segments in the region frame, its freespace, and its scans' arcs.
struct ScanPoints
{
  Eigen::Vector2d origin;                   // laser position, region frame
  std::vector<Eigen::Vector2d> points;      // region frame, beam order
};

// Rectangles from the merged line map; `freespace` decides object vs. wall (an empty bitmap
// gives no rectangles). Ids are left 0.
std::vector<rgmap::Object2d> group_rectangles(const std::vector<rgmap::LineSegment>& segments,
                                              const rgmap::FreespaceBitmap& freespace, const ObjectOptions& o);

// Circle observation of one scan arc, if any: centre (region frame) and radius.
struct CircleObservation
{
  Eigen::Vector2d center;
  double radius = 0;
};
std::vector<CircleObservation> circles_in_scan(const ScanPoints& scan, const ObjectOptions& o);

// Circles seen in enough scans (clustered observations), centres not free. Ids are left 0.
std::vector<rgmap::Object2d> cluster_circles(const std::vector<CircleObservation>& observations,
                                             const rgmap::FreespaceBitmap& freespace, const ObjectOptions& o);

// Both, with ids region_id * 1000 + k (objects are recomputed whenever the region changes;
// the id is stable as long as the set of objects is).
std::vector<rgmap::Object2d> find_objects(int64_t region_id, const std::vector<rgmap::LineSegment>& segments,
                                          const std::vector<CircleObservation>& circle_observations,
                                          const rgmap::FreespaceBitmap& freespace, const ObjectOptions& o);

// Smallest distance between two segments (0 if they cross).
double segment_distance(const rgmap::LineSegment& s, const rgmap::LineSegment& t);
// Gap between two non-parallel segments at the corner they would form: how far the farther of
// the two is from the intersection of their lines (0 if they really intersect; infinity if
// the lines are parallel).
double corner_gap(const rgmap::LineSegment& s, const rgmap::LineSegment& t);

}  // namespace rgnav::rg_kernel
