// Gateways as boundaries of regions' free space (diss. 5.2: beams that cross a gateway are not
// the region's). A narrow passage is one line; a crossing is the outline of the junction (the
// gateway detector's four points: entry, left, ahead and right sides, diss. fig. 4.1). The
// junction is shared by the regions it joins: a region's beams may enter it through the sides
// its robot came in or left by, and end where they leave it through any other side. Every other
// region's beams end where they first cross its outline.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <utility>
#include <vector>

#include "geometry/segment2.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

using Line = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

// Where the ray from `origin` along `dir` (unit) meets the line through a and b: the distance
// along the ray (negative: behind it) and the position along a -> b (0 at a, 1 at b); nullopt
// if they are parallel, which for the kernel is |cross(dir, b - a)| < 1e-9.
inline std::optional<geometry::RayHit> ray_meets_line(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                                      const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  return geometry::ray_meets_line(origin, dir, a, b, 1e-9);
}

// The boundary lines of one gateway: four points are a closed outline (its four sides),
// otherwise consecutive point pairs are lines.
std::vector<Line> gateway_edges(const std::vector<Eigen::Vector2d>& points);

// A gateway line with its own frame: midpoint, unit direction, unit normal (for an outline
// pointing out of it, otherwise to the left of the line's direction) and length.
struct EdgeFrame
{
  Line line;
  Eigen::Vector2d mid, along, normal;
  double length = 0.0;

  // Whether p lies beyond the line along its normal, at least `min_depth` and less than `reach`
  // from it, and not beside its ends (a robot leaving diagonally, pose noise: up to 0.5 m beside
  // them still counts).
  bool just_beyond(const Eigen::Vector2d& p, double reach, double min_depth = 0.0) const;
};

// When a region lies beyond a side of a crossing's outline: one of its robot positions is
// just_beyond the side with these. A position a few cm past the line is on it (pose noise, the
// scan before the detector's late report, a turn on the line; along a row of cubicles, one such
// position opened every cubicle's stem side to a hallway region's beams).
struct SideReach
{
  double reach = 2.0;       // [m]
  double min_depth = 0.0;   // [m]
};

// gateway_edges with their frames; zero-length lines are left out.
std::vector<EdgeFrame> edge_frames(const std::vector<Eigen::Vector2d>& points);

// Whether the line p-q (a door or narrow passage) lies along a side of `outline` (a crossing's
// four points) that a crossing with `heading` [rad] goes in or out through: parallel to the side
// (within 20 deg), its midpoint within `tolerance` of the side's line and between its ends. The gateway detector sees a door in a hallway wall as
// the branch of a junction (diss. 4.1: the VLM hypotheses look alike), and reports the one
// crossing through it twice: as the door and as the junction left or entered through the door.
bool line_on_crossed_side(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                          double heading, double tolerance);

// [m] The longest stretch of `side` that no wall runs along: walls are line-map segments
// parallel to it (within 15 deg) with both ends within `tolerance` of its line. A crossing's
// side with a branch behind it is open over about the branch's width; a hallway wall with a
// door in it, at most over the door.
double widest_opening(const Line& side, const std::vector<rgmap::LineSegment>& walls, double tolerance);

// The line l lengthened by `by` at both ends (unchanged if it has no length).
Line lengthened(const Line& l, double by);

// The lines of one gateway (points in the region frame) that end the beams of a region whose
// robot stood at `origins` (region frame): all its edges, except for an outline the sides with
// one of the origins just outside them (just_beyond with `side_reach`):
// the region lies beyond those.
// A line (not an outline) is lengthened by `line_extension` at both ends: the detector's door
// points lie on the jambs' visible edges, and beams grazing past them still went through the door.
std::vector<Line> clip_lines(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& origins,
                             const SideReach& side_reach, double line_extension = 0.0);

// What makes a side of a crossing's outline walled or open in a line map (widest_opening): open
// over at least `min_open` (or 80 % of the side, if shorter), walls within `tolerance` of it.
struct OpeningTest
{
  double min_open = 1.4;     // [m]
  double tolerance = 0.25;   // [m]
  bool open(const EdgeFrame& side, const std::vector<rgmap::LineSegment>& walls) const;
};

// A side of a crossing's outline (outward normal) and the outline's depth behind it (the longer of
// the sides beside it).
struct StemSide
{
  EdgeFrame side;
  double depth = 0.0;
};

// Which sides of a crossing's outline are stems: both sides beside open in the line map (a
// hallway runs past), and for a T the side opposite walled too; for an X the side opposite may be
// open (another branch: cubicles facing each other across a narrow hallway).
enum class StemKind { kT, kTOrX };

// The sides of a crossing's outline (four points) that a region whose robot stood at `origins`
// lies beyond (as clip_lines opens them) and that are stems of `kind` in `walls`. A hallway runs
// past such a side and the branch behind it (a room, a bay, a side hallway) ends there: the
// junction's square is the hallway's (Bormann et al.'s ground truth ends rooms at the hallway
// wall's line).
std::vector<StemSide> stems_entered(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& origins,
                                    const SideReach& side_reach, const std::vector<rgmap::LineSegment>& walls, const OpeningTest& test,
                                    StemKind kind = StemKind::kT);

}  // namespace rgnav::rg_kernel
