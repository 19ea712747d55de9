// Chains built directly from a start and an end pose (diss. 5.5.3: "if possible, these
// trajectory segments are directly determined given start and end poses"). Each returns
// nothing when its shape cannot connect the two poses.
#pragma once

#include <optional>

#include "trajectory/chain.h"

namespace rgnav::trajectory {

// Line, circular arc, line through the corner where the two heading lines meet (the arc is
// as wide as the shorter leg allows). Curvature jumps at the joints (G1).
std::optional<Chain> line_arc_line(const Pose2& start, const Pose2& end, double kappa_max);

// The same corner with a clothoid-arc-clothoid turn: curvature continuous (G2), so a drive
// can follow it at speed without a step in rotational velocity.
std::optional<Chain> line_turn_line_g2(const Pose2& start, const Pose2& end, double kappa_max);

// A single clothoid joining the two poses (G1 Hermite interpolation, Bertolazzi & Frego
// 2015, "G1 fitting with clothoids"): solves for the curvature change by Newton's method.
std::optional<Segment> clothoid_g1(const Pose2& start, const Pose2& end);

// Clothoid-arc-clothoid turn by dtheta, curvature ramped 0 -> kappa -> 0 (kappa > 0); a
// third of the heading change is made in each part. G2 at both ends for a straight approach
// and exit.
Chain smooth_turn(const Pose2& start, double dtheta, double kappa);

// Shortest Dubins path (arcs of radius 1/kappa and lines, words LSL RSR LSR RSL RLR LRL).
std::optional<Chain> dubins(const Pose2& start, const Pose2& end, double kappa);

// Quarter ellipse when the heading turns by +-90 deg and the end lies ahead on that side:
// semi-axes are the forward and sideways offsets.
std::optional<Segment> quarter_ellipse(const Pose2& start, const Pose2& end, double tolerance = 1e-6);

}  // namespace rgnav::trajectory
