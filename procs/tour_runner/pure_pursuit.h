// The simple waypoint follower the demo uses until the low-level drive and collision
// avoidance run: pure pursuit toward the next target, turning in place when the target is
// behind, and slowing / stopping for laser returns in the driving corridor. Fail safe:
// without a recent scan it commands zero.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::tour_runner {

struct PursuitOptions
{
  double max_v = 0.5;            // [m/s]
  double max_omega = 1.0;        // [rad/s]
  double turn_in_place_angle = 1.0;  // [rad] larger heading error: rotate without translating
  double robot_radius = 0.26;    // [m]
  double stop_distance = 0.15;   // [m] clearance at which the robot stops
  double slow_distance = 0.8;    // [m] clearance below which speed scales down
};

struct Command
{
  double v = 0;
  double omega = 0;
  bool blocked = false;   // stopped by an obstacle
  // When blocked: the free heading (base frame, rad) closest to the target, NaN if none.
  double escape_heading = std::numeric_limits<double>::quiet_NaN();
};

// obstacles: laser end points in the base frame.
Command pursue(const PursuitOptions& o, const geometry::Pose2& odom_from_base, const Eigen::Vector2d& odom_target,
               const std::vector<Eigen::Vector2d>& obstacles_in_base);

// Leaving a blocked spot: turn to `heading_error` (the committed free heading relative to the
// robot's), then creep along it while it stays free. Committing to that heading for a short
// distance is what keeps the follower from turning back into the obstacle at once.
Command escape(const PursuitOptions& o, double heading_error, const std::vector<Eigen::Vector2d>& obstacles_in_base);

}  // namespace rgnav::tour_runner
