// Where a goal last failed from: the robot's place and the RG map's version then. A goal that
// fails again from the same place on the same map says nothing new (the planner's answer is the
// same), so that failure is no attempt of its own (ExplorerOptions::max_attempts): a robot that
// stands still does not set everything aside. Kept per goal: a failure of one goal says nothing
// about another (with one record for all, a robot that tried three unreachable gateways in a row
// counted only the first of them, the others never ran out of attempts, and exploring never
// ended).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>

namespace rgnav::explorer {

struct LastFailure
{
  Eigen::Vector2d robot{0, 0};     // [m] map frame
  int64_t map_version = 0;
};

// Whether failing from `now` tells more than the goal's last failure `last` (none: yes): the
// robot stands at least moved_m from where it failed then, or the map changed since.
bool tells_more(const std::optional<LastFailure>& last, const LastFailure& now, double moved_m);

// State files: [x, y, map_version]; last_failure_from_json throws std::invalid_argument on anything else.
nlohmann::json last_failure_json(const LastFailure& f);
LastFailure last_failure_from_json(const nlohmann::json& j);

}  // namespace rgnav::explorer
