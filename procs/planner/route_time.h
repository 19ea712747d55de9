// The expected time of a route (diss. 5.5.3: the time to drive a chain of trajectory segments is
// predicted accurately, so it can rate paths): the route's path as a chain of lines with a
// line-arc-line corner at every bend (curvature bounded by the turn the drive makes at speed;
// a bend too sharp for that turns in place), and the trajectory library's velocity profile
// under the drive's limits, from standing to standing.
#pragma once

#include "planner/route.h"
#include "trajectory/velocity_profile.h"

namespace rgnav::planner {

// [s] from the route's start to its end; route.length / limits.v_max if it has no length.
double predicted_time(const Route& route, const trajectory::Limits& limits);

}  // namespace rgnav::planner
