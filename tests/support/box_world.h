// An empty square room for simulator tests: the walls of box(-half, -half, half, half)
// (wall_world.h) at the simulator's default heights, the robot starting at the centre.
#pragma once

#include "sim/world.h"
#include "wall_world.h"

namespace rgnav::testing {

inline sim::World box_world(double half = 10.0)
{
  sim::World w;
  w.name = "box";
  w.start = {0.0, 0.0, 0.0};
  for (const auto& side : box(-half, -half, half, half)) {
    sim::Wall wall;
    wall.a = side.a;
    wall.b = side.b;
    w.walls.push_back(wall);
  }
  return w;
}

}  // namespace rgnav::testing
