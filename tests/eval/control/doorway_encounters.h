// The doorway_encounters section of control_bench: the generated encounters of doorway_world.h
// driven closed-loop (simulated B21r with odometry drift and the ray-cast LMS 2xx, collision
// avoidance, the lld follower, targets re-expressed through a perfect localizer as the demo's
// planner would), each once with the person and once without (the robot's own time there).
//
// What it counts (the same words in the JSON's notes):
//   - resolved: the robot arrived at its goal beyond the opening within the time bound, its own
//     time without the person plus kResolveBound_s (60 s);
//   - deadlock: neither party made progress for kDeadlock_s (20 s) before the robot arrived:
//     the robot came no closer to its goal than 0.2 m nearer than it was at its last progress
//     (or the farthest since: having given way, coming back counts), and the person moved less
//     than 0.2 m from where they were at the start of that stretch (whichever way: turning
//     back is progress out of a standoff) and was not at their destination. Ended by the time
//     bound, it still counts;
//   - collision: what the control bench counts on its obstacle courses: the simulator's
//     contacts, the robot's own motion bringing its body into a wall or a person (people stop
//     short of the robot, they never step into it);
//   - time lost: time to the goal with the person minus without, over the resolved encounters.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>

#include "collision_avoidance/collision_avoidance.h"
#include "lld/lld_options.h"

namespace rgnav::bench {

constexpr double kResolveBound_s = 60.0;
constexpr double kDeadlock_s = 20.0;
constexpr double kProgress_m = 0.2;

// `n` encounters (seeded); only >= 0: run that one alone (debugging; CB_DEBUG=1 traces it,
// CB_DEBUG_EVERY=N every N control periods, CB_DEBUG_TRACKS=1 with the people tracker's tracks).
nlohmann::json doorway_encounters(const lld::LldOptions& lld_options, const collision_avoidance::CaOptions& ca_options,
                                  int n, uint64_t seed, int only);

}  // namespace rgnav::bench
