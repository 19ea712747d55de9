// What a page may send the viewer, and nothing else: a goal (a region, optionally a pose in
// its frame) or the cancel of one, as one small JSON text frame. Anything else is malformed,
// and the server closes that client (and only that one).
//   {"type":"goal","region_id":3,"token":"..."}
//   {"type":"goal","region_id":3,"pose":[x,y,theta],"token":"..."}   (region frame, m, rad)
//   {"type":"cancel","token":"..."}
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "geometry/pose2.h"

namespace rgnav::viewer {

struct GoalRequest
{
  bool cancel = false;
  int64_t region_id = 0;
  std::optional<geometry::Pose2> region_pose;
  std::string token;
};

// nullopt with *why set when `text` is not exactly one of the forms above.
std::optional<GoalRequest> parse_client_input(const std::string& text, std::string* why);

// Goals from the viewer's own host are trusted (whoever can reach loopback can run ./rgnav goto);
// from another host they need the configured token, and with no token configured they are refused.
bool goal_allowed(const GoalRequest& request, bool from_loopback, const std::string& token, std::string* why);

}  // namespace rgnav::viewer
