// A tour: waypoints in the world (map) frame and the pose the robot starts at, read from a
// world or tour file (keys `start: [x, y, theta]` and `tour: [[x, y], ...]` or the world
// format's flat `tour: [x0, y0, x1, y1, ...]`; other keys of a world file are ignored).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::tour_runner {

struct Tour
{
  geometry::Pose2 world_from_start;            // robot pose when odometry started
  std::vector<Eigen::Vector2d> world_points;   // waypoints in the world frame, in order
};

// Throws config::ConfigError naming the file and key.
Tour load_tour(const std::string& path);

// Inserts points so that consecutive waypoints are at most max_spacing apart (targets for
// collision avoidance are 0.5-2 m apart).
std::vector<Eigen::Vector2d> densify(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& from,
                                     double max_spacing);

}  // namespace rgnav::tour_runner
