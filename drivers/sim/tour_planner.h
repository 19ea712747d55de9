// Tours through a world: a collision-free sequence of waypoints from the start pose that
// enters every reachable labelled region (rooms, lobby, hallways) and returns to the start,
// closing the loop. Planned on a 5 cm grid of the robot's configuration space (cells whose
// clearance to anything the body could hit, at the doors' state at time 0, exceeds radius +
// margin), ordered greedily by path length, smoothed by line of sight, and checked again
// against the exact geometry.
#pragma once

#include <string>
#include <vector>

#include "sim/simulator.h"
#include "sim/world.h"

namespace rgnav::sim {

struct TourOptions
{
  double resolution = 0.05;      // [m] planning grid
  double margin = 0.08;          // [m] kept free beyond the robot radius
  double comfort_distance = 0.6; // [m] paths prefer this much clearance
  double max_leg = 4.0;          // [m] longest straight leg between waypoints
};

struct Tour
{
  std::vector<Vec2> waypoints;       // first = start position, last = start again
  std::vector<std::string> visited;  // regions the tour passes through, in order of first entry
  std::vector<std::string> unreachable;
  double length = 0.0;               // [m]
  bool collision_free = false;       // verified against the exact geometry
};

Tour plan_tour(const World& world, const RobotOptions& robot, const TourOptions& options = {});

// The waypoints of `laps` times round the tour: each lap after the first starts from the
// previous lap's last waypoint (the start), which is not repeated.
std::vector<Vec2> laps_route(const Tour& tour, int laps);

// Minimum clearance of the polyline to obstacles the body could hit (static geometry and
// doors at time 0; people are not obstacles for planning).
double polyline_clearance(const World& world, const RobotOptions& robot, const std::vector<Vec2>& polyline);

// Names of the regions the polyline passes through (sampled every 5 cm), in order of first entry.
std::vector<std::string> regions_along(const World& world, const std::vector<Vec2>& polyline);

std::string tour_to_yaml(const World& world, const Tour& tour);

}  // namespace rgnav::sim
