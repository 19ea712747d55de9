// Giving way when the robot and someone wait for each other (diss. 5.5.3's fallback layer):
// a person walking toward the robot stops at their personal space and waits for the robot to
// clear their way; the robot, whose way to the target leads past that person, waits for them.
// Backing off from what is near (the repulsion of everything within reach) does not break
// this: between a box, a wall and the person, "away" points at the person's side or at a
// wall, and the robot only turns on the spot. What does break it is leaving the person's way:
// back, away from the target, since that is where the robot wanted to pass and where the person
// waits. Among headings within `spread` of straight back, the straight line from the robot
// that stays free (the planner's footprint check) for longest wins, weighted by how directly
// it leads back.
#pragma once

#include <optional>

#include "collision_avoidance/local_map.h"

namespace rgnav::collision_avoidance {

struct GiveWayOptions
{
  double length = 1.0;       // [m] how far to drive back at most
  double min_length = 0.3;   // [m] shorter free lines do not count
  double spread = 1.57;      // [rad] headings up to this far either side of straight back
  int headings = 9;          // tried over [-spread, spread]
};

struct GiveWay
{
  double heading = 0.0;  // [rad] odom frame
  double length = 0.0;   // [m] free along it
};

// `away`: the heading straight back from the target (odom frame). clearance: robot radius +
// safety margin; step: the footprint check's step. Nothing if no line is free for min_length.
std::optional<GiveWay> choose_give_way(const LocalMap& map, const Eigen::Vector2d& from, double away, double clearance,
                                       double step, const GiveWayOptions& options);

}  // namespace rgnav::collision_avoidance
