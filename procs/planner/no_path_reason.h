// Why a goal has no path, as GLOBAL_PATH's reason begins (global_path_t.reason: text for people,
// whose first words a goal's sender may read): the robot's own place joins nothing (standing
// where it is, nothing will change: change the view or step away), or the goal cannot be reached
// from where the robot is (another goal, or later), or only a gateway taken for closed for a
// while is in the way (the same goal again once it reopens), or only places collision avoidance
// could not pass a moment ago (held for a while: people standing about, or what the line map
// holds too thinly; the same goal again once they are let go). Header only: the explorer reads the
// causes from the planner's reasons without linking the planner.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace rgnav::planner {

enum class NoPathCause : int8_t {
  kOther = 0,
  kStartCutOff = 1,
  kGoalUnreachable = 2,
  kClosedGateway = 3,
  kBlockedPlace = 4
};

inline constexpr std::string_view kStartCutOffReason = "start cut off: ";
inline constexpr std::string_view kGoalUnreachableReason = "goal unreachable: ";
inline constexpr std::string_view kClosedGatewayReason = "behind a closed gateway: ";
inline constexpr std::string_view kBlockedPlaceReason = "behind a blocked place: ";

inline std::string no_path_reason(NoPathCause cause, const std::string& detail)
{
  switch (cause) {
    case NoPathCause::kStartCutOff: return std::string(kStartCutOffReason) + detail;
    case NoPathCause::kGoalUnreachable: return std::string(kGoalUnreachableReason) + detail;
    case NoPathCause::kClosedGateway: return std::string(kClosedGatewayReason) + detail;
    case NoPathCause::kBlockedPlace: return std::string(kBlockedPlaceReason) + detail;
    case NoPathCause::kOther: break;
  }
  return detail;
}

inline NoPathCause no_path_cause(std::string_view reason)
{
  const auto starts = [&](std::string_view prefix) { return reason.substr(0, prefix.size()) == prefix; };
  if (starts(kStartCutOffReason)) return NoPathCause::kStartCutOff;
  if (starts(kGoalUnreachableReason)) return NoPathCause::kGoalUnreachable;
  if (starts(kClosedGatewayReason)) return NoPathCause::kClosedGateway;
  if (starts(kBlockedPlaceReason)) return NoPathCause::kBlockedPlace;
  return NoPathCause::kOther;
}

}  // namespace rgnav::planner
