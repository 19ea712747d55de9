// Generated doorway and narrow-hallway encounters for control_bench: two rooms joined by an
// opening in the wall between them, a doorway (the wall 0.1-0.3 m thick) or a hallway (2.5-6 m
// long), of a width drawn between what the robot just fits through and what a person standing
// aside leaves the robot room beside. The robot starts in one room and has to reach a goal in
// the other; one person walks the other way through the opening, starting so that they reach it
// from 5 s before to 5 s after the robot would (meeting it before, in or beyond the opening), at
// a speed of their own, with a personal space and a patience of their own, and doing at random
// what people do when the robot is in their way (sim/people.h: wait, stand aside, go around;
// patience run out and no room: turn back).
#pragma once

#include <random>
#include <string>
#include <vector>

#include "geometry/pose2.h"
#include "sim/world.h"

namespace rgnav::bench {

struct DoorwayEncounter
{
  std::string kind;       // "doorway" or "hallway"
  double width = 0.0;     // [m] of the opening
  double depth = 0.0;     // [m] wall thickness / hallway length
  sim::World world;       // walls, the robot's start, the person (World::people[0])
  geometry::Pose2 goal;   // world frame, in the far room
  std::vector<geometry::Pose2> targets;  // world frame, start to goal through the opening, <= 1 m apart
  double person_lead_s = 0.0;  // the person reaches the opening this much before the robot would (negative: after)
};

// Encounter `index` (even: doorway, odd: hallway) drawn from `rng`. `clearance`: the robot's
// radius plus safety margin; the opening leaves it at least 0.06 m more on either side.
DoorwayEncounter draw_doorway_encounter(std::mt19937& rng, int index, double clearance);

}  // namespace rgnav::bench
