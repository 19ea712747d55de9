// The untraversed gateways (diss. ch. 7: every gateway found and not yet gone through is kept
// on a stack and visited breadth-first, so that the map grows outward from the start and a loop
// is closed from a region seen long ago only rarely). The RG map holds a gateway only once it
// has been traversed; before that the gateway detector's sightings are what is known of it.
// A sighting becomes an entry per exit heading (a crossing's branches are entries of their
// own), in the map frame, with the region it was seen from. An entry is done once the robot has
// been past it, or once the place beyond it is free in some region of the map the robot has left
// (seen from elsewhere); an entry the planner could not reach is set aside with the reason and tried
// again later (ExplorerOptions::retry_after_s, max_attempts); one set aside for good is tried
// again once the map near it changed (place_view.h).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "explorer/explorer_options.h"
#include "explorer/last_failure.h"
#include "explorer/place_view.h"
#include "rgmap/rg_map.h"

namespace rgnav::explorer {

// One gateway the detector reports, in the map frame.
struct GatewaySighting
{
  rgmap::GatewayClass cls = rgmap::GatewayClass::kUnknown;
  Eigen::Vector2d crossing{0, 0};       // [m] map frame: where a path crosses it
  std::vector<double> headings;         // [rad] map frame: exit headings through it
  int observations = 0;                 // scans the detector has tracked it over
};

struct StackEntry
{
  enum class State : int8_t { kPending = 0, kDone = 1, kSetAside = 2 };
  int64_t id = 0;
  rgmap::GatewayClass cls = rgmap::GatewayClass::kUnknown;
  Eigen::Vector2d crossing{0, 0};       // [m] map frame
  double heading = 0;                   // [rad] map frame, the exit heading
  int64_t region_id = 0;                // the region it was seen from
  int64_t utime = 0;                    // first seen
  State state = State::kPending;
  int attempts = 0;                     // goals for it that failed
  int closed_failures = 0;              // goals for it only a gateway held closed was in the way of (no attempts)
  int64_t retry_utime = 0;              // set aside: not before this
  int64_t map_regions_at_failure = 0;   // regions in the map when it last failed (a new one: retry)
  int64_t failed_utime = 0;             // when it last failed
  PlaceView view_at_failure;            // the map around its crossing then
  std::optional<LastFailure> failed_from;   // where the robot stood then, on which map
  std::string reason;                   // why done or set aside
  // The goal beyond it (map frame).
  Eigen::Vector2d beyond(double distance) const;
};

class GatewayStack
{
 public:
  explicit GatewayStack(StackOptions options = {}) : options_(options) {}

  // Adds the sighting's exit headings seen from `region_id` as entries, or refreshes entries
  // they match; headings into space the map knows as free are not stacked.
  void add(const GatewaySighting& s, int64_t region_id, int64_t utime, const rgmap::RgMap& map);
  // Marks done what the robot (map frame position) has gone past, and what the map now knows
  // beyond; returns the number marked.
  int update(const Eigen::Vector2d& robot, const rgmap::RgMap& map);
  // Pending entries in the order they are to be visited: breadth-first (fewest RG-graph hops
  // from `start_region` to the entry's region, then nearest to `robot`), or nearest first;
  // set-aside entries whose retry is due (utime and map) follow, in the same order.
  std::vector<const StackEntry*> order(const rgmap::RgMap& map, int64_t start_region, const Eigen::Vector2d& robot,
                                       int64_t utime) const;
  void done(int64_t id, const std::string& reason);
  // A goal for entry `id` failed: set aside until `retry_utime` (and for good after max attempts;
  // `counts` false: not an attempt, the same failure again from the same place on the same map).
  // `view`: the map around its crossing now (place_view.h); `from`: where the robot stood.
  // `max_closed_retries` > 0: only a gateway held closed was in the way (no attempt), and the
  // max_closed_retries-th such failure sets it aside for good.
  void failed(int64_t id, const std::string& reason, int64_t utime, int64_t retry_utime, int max_attempts,
              int64_t map_regions, const PlaceView& view, bool counts = true, int max_closed_retries = 0,
              std::optional<LastFailure> from = std::nullopt);
  // Entries set aside for good whose surroundings changed since they last failed (and that failed
  // at least `min_age_us` before `utime`) are due again, with one attempt left; returns how many.
  int release_changed(const rgmap::RgMap& map, const PlaceViewOptions& o, int64_t utime, int64_t min_age_us,
                      int max_attempts);

  const StackEntry* entry(int64_t id) const;
  const std::vector<StackEntry>& entries() const { return entries_; }
  int count(StackEntry::State s) const;

  nlohmann::json to_json() const;
  // Throws std::invalid_argument on a malformed document.
  void from_json(const nlohmann::json& j);

 private:
  StackOptions options_;
  std::vector<StackEntry> entries_;
  int64_t next_id_ = 1;
};

}  // namespace rgnav::explorer
