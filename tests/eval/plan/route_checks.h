// What the planning benchmark checks on one of rgnav's routes: that it is well formed (legs that
// join, the start and goal where asked, lengths that add up), laid into the map frame through
// each region's map_from_region, the whole grid's clearance along it; and the picture of a few
// routes beside their references.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "occupancy_grid.h"
#include "planner/route.h"
#include "rgmap/rg_map.h"
#include "standable_points.h"

namespace rgnav::plan_eval {

double polyline_length(const std::vector<Eigen::Vector2d>& points);

// A route checked against its request and laid into the map frame.
struct CheckedRoute
{
  std::vector<Eigen::Vector2d> map_points;   // every leg through its region's map_from_region
  double length = 0;                         // [m] legs plus the gaps where consecutive legs meet
  double join_gap_max = 0;                   // [m]
  std::string defect;                        // "" when the route is well formed
};
CheckedRoute check_route(const rgmap::RgMap& map, const planner::Route& route, const RegionPoint& start, const RegionPoint& goal,
                         double adapt_distance);

// The whole grid's clearance along a map-frame polyline, every cell: overall minimum, mean, and
// minimum (and where) farther than end_m along the line from both ends.
struct SampledClearance
{
  double min = INFINITY, mean = 0, interior_min = INFINITY;
  Eigen::Vector2d interior_min_at{0, 0};   // map frame
};
SampledClearance sample_clearance(const ConfigSpace& space, const std::vector<Eigen::Vector2d>& points, double end_m);

// A route (red) and its reference (blue), map frame.
struct DrawnPair
{
  std::vector<Eigen::Vector2d> route, reference;
};
// The whole grid (free white, inside the robot radius of a wall tinted, unknown grey, occupied
// black) with the pairs drawn, as an image file.
void draw_routes(const ConfigSpace& space, const std::vector<DrawnPair>& pairs, const std::string& path);

}  // namespace rgnav::plan_eval
