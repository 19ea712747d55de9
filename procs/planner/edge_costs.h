// What the planner learns about the RG graph's edges while the robot drives (diss. 5.4): the
// measured time to cross a region between two of its gateways and to cross a gateway; for a
// door, an extra cost raised by a fixed amount whenever it could not be passed and lowered when
// it could, never below its real crossing time; a gateway found closed is left out of planning
// until a retry time (doubling with every failure in a row: a door shut for the night is not
// tried every half minute, one blocked by people for a moment is soon tried again). The doubled
// part of that hold only steers routes round the gateway: where held gateways are all that is in
// the way, one closed_retry_s past its last failure is planned through again (ClosedHold::kBase).
// Before, a robot whose only way on had failed a few times in a row (collision avoidance under
// load, a door shut for a while) waited up to 32 x closed_retry_s with nothing else to do. Keys are
// map ids (stable across map versions and restarts), so the node saves this beside its state
// and a restarted planner keeps it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <tuple>

#include "planner/planner_options.h"
#include "rgmap/rg_map.h"

namespace rgnav::planner {

// How a gateway found closed is left out of planning: for its whole hold (doubled with every
// failure in a row), for closed_retry_s after its last failure only, or not at all.
enum class ClosedHold : int8_t { kWhole = 0, kBase = 1, kNone = 2 };

class EdgeCosts
{
 public:
  explicit EdgeCosts(const GlobalOptions& options) : options_(options) {}

  // [s] cost of crossing gateway g at message time now_s; nullopt while it counts as closed
  // (under `hold`).
  std::optional<double> gateway_cost(const rgmap::Gateway& g, double now_s, ClosedHold hold = ClosedHold::kWhole) const;
  // [s] cost of crossing `region` between the crossing points of two gateways (0: the robot's
  // start or goal inside it), given the planned path length: the learned time once measured.
  double region_cost(int64_t region, int64_t gateway_from, int64_t gateway_to, double planned_length) const;
  bool measured(int64_t region, int64_t gateway_from, int64_t gateway_to) const;

  // The robot crossed gateway g taking `seconds`: its time is learned, a door's extra lowered,
  // any closed mark lifted.
  void gateway_passed(const rgmap::Gateway& g, double seconds);
  // Gateway g could not be passed at now_s: its extra raised (doors), closed until the retry time.
  void gateway_failed(const rgmap::Gateway& g, double now_s);
  bool closed(int64_t gateway_id, double now_s, ClosedHold hold = ClosedHold::kWhole) const;
  // The robot crossed `region` between two gateways' crossing points taking `seconds`.
  void region_traversed(int64_t region, int64_t gateway_from, int64_t gateway_to, double seconds);

  int64_t changes() const { return changes_; }   // increases with every learned change (for saving)

  nlohmann::json to_json() const;
  // Throws std::invalid_argument naming the key when j is not what to_json writes.
  void from_json(const nlohmann::json& j);

 private:
  struct GatewayRecord
  {
    double time = 0;          // [s] learned crossing time (0: not measured)
    int passes = 0, failures = 0;
    int failures_in_a_row = 0;   // since the last pass: each doubles the time it stays closed
    double extra = 0;         // [s] door extra beyond the base door_extra_time, >= 0
    double closed_until = 0;  // [s] message time; 0: not closed
    double failed_at = 0;     // [s] message time of the last failure
  };
  bool held(const GatewayRecord& r, double now_s, ClosedHold hold) const;
  using RegionKey = std::tuple<int64_t, int64_t, int64_t>;   // region, smaller gateway, larger gateway
  static RegionKey region_key(int64_t region, int64_t a, int64_t b);

  GlobalOptions options_;
  std::map<int64_t, GatewayRecord> gateways_;
  std::map<RegionKey, double> region_times_;   // [s]
  int64_t changes_ = 0;
};

}  // namespace rgnav::planner
