// The built-in worlds, generated deterministically (no randomness beyond a fixed-seed Rng)
// and checked in as YAML under config/worlds/ by `sim_worldgen` (a test verifies that the
// files are what the generator writes):
//   office                — an office floor in the spirit of the dissertation's experiments:
//                           two long hallways crossing, a loop with turns and a T-junction,
//                           15 offices with doors (some cluttered, one closed until later),
//                           a lobby, people walking;
//   hallways_<w>_<c>      — the hallway environments of dissertation 4.1.4: width 2, 2.5 or
//                           3 m, clutter none / slight / strong, with every crossing class
//                           (X, T, LT, RT, L-turn, R-turn) and dead ends.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/world.h"

namespace rgnav::sim {

enum class Clutter { kNone, kSlight, kStrong };

World office_world();
World hallway_world(double width, Clutter clutter);
// Every built-in world with its file stem.
std::vector<std::pair<std::string, World>> builtin_worlds();

}  // namespace rgnav::sim
