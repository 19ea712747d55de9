// A planned route: legs, one per region on the way, each a path in that region's frame from
// where the robot enters (its start, or a gateway's crossing point) to where it leaves (the next
// gateway's crossing point, or the goal).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::planner {

struct RouteLeg
{
  int64_t region_id = 0;
  int64_t entry_gateway = 0;                 // 0: the start is in this region
  int64_t exit_gateway = 0;                  // 0: the goal is in this region
  std::vector<Eigen::Vector2d> points;       // region frame
  double length = 0;                         // [m]
  double min_clearance = 0;                  // [m]
  // The next leg's frame in this one's (through exit_gateway); identity for the last leg.
  geometry::Pose2 this_from_next;
};

// A target for collision avoidance, fixed along the route when it is planned (so that re-sending
// the upcoming ones gives the same points until one is passed).
struct RouteTarget
{
  size_t leg = 0;            // leg whose frame `pose` is in
  double arc = 0;            // [m] along the whole route
  geometry::Pose2 pose;      // headed along the path (the goal heading for the last, if given)
};

struct Route
{
  std::vector<RouteLeg> legs;
  std::vector<RouteTarget> targets;   // cut_targets()
  double cost_s = 0;          // [s] what the search minimised (times, with the wall and door costs)
  double expected_s = 0;      // [s] predicted driving time, start to goal (route_time.h)
  double length = 0;          // [m]
  int64_t map_version = 0;
  double goal_heading = 0;    // [rad] in the last leg's frame
  bool has_goal_heading = false;
  bool empty() const { return legs.empty(); }
  // Gateways crossed, in order.
  std::vector<int64_t> gateways() const;
  // [m] arc length of the route where leg `leg` begins.
  double leg_start(size_t leg) const;
  // Leg `to`'s frame in leg `from`'s (from <= to), through the gateways between.
  geometry::Pose2 frame_of(size_t from, size_t to) const;
};

// Targets along the whole route: every bend of the path at least spacing_min (along the path)
// past the last target, and nearer ones too (down to 0.25 m) where the path bends by more than
// 0.1 m or crosses a gateway, so that the line between two targets does not cut a corner the
// path goes round; long stretches divided so that targets are at most spacing_max apart. The
// last target is the route's end. Each is in the frame of the leg it lies in.
std::vector<RouteTarget> cut_targets(const Route& route, double spacing_min, double spacing_max);

// The point of the leg's path `arc` metres from its start (its ends beyond them).
Eigen::Vector2d point_along(const RouteLeg& leg, double arc);

// Where p (leg `leg`'s frame) projects onto that leg's path, as arc length from its start, not
// before `from` (progress only moves forward); *distance gets how far p is from the path.
double project_onto_leg(const RouteLeg& leg, const Eigen::Vector2d& p, double from, double* distance);

}  // namespace rgnav::planner
