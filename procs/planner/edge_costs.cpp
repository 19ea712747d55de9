#include "planner/edge_costs.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rgnav::planner {

namespace {

double blend(double old_value, double measured, double rate)
{
  return old_value > 0 ? (1.0 - rate) * old_value + rate * measured : measured;
}

}  // namespace

EdgeCosts::RegionKey EdgeCosts::region_key(int64_t region, int64_t a, int64_t b)
{
  return {region, std::min(a, b), std::max(a, b)};
}

bool EdgeCosts::held(const GatewayRecord& r, double now_s, ClosedHold hold) const
{
  switch (hold) {
    case ClosedHold::kWhole: return now_s < r.closed_until;
    case ClosedHold::kBase: return now_s < std::min(r.closed_until, r.failed_at + options_.closed_retry_s);
    case ClosedHold::kNone: return false;
  }
  return false;
}

std::optional<double> EdgeCosts::gateway_cost(const rgmap::Gateway& g, double now_s, ClosedHold hold) const
{
  double cost = options_.crossing_time;
  const auto it = gateways_.find(g.id);
  if (it != gateways_.end()) {
    if (held(it->second, now_s, hold)) return std::nullopt;
    if (it->second.time > 0) cost = it->second.time;
  }
  if (g.cls == rgmap::GatewayClass::kDoor) {
    // Doors cost more than hallway gateways (diss. 5.4), more still each time one was closed.
    cost += options_.door_extra_time + (it != gateways_.end() ? it->second.extra : 0.0);
  }
  return cost;
}

double EdgeCosts::region_cost(int64_t region, int64_t gateway_from, int64_t gateway_to, double planned_length) const
{
  const double planned = planned_length / options_.nominal_speed;
  if (gateway_from == 0 || gateway_to == 0) return planned;   // start or goal: never measured
  const auto it = region_times_.find(region_key(region, gateway_from, gateway_to));
  return it != region_times_.end() ? it->second : planned;
}

bool EdgeCosts::measured(int64_t region, int64_t gateway_from, int64_t gateway_to) const
{
  return gateway_from != 0 && gateway_to != 0 && region_times_.count(region_key(region, gateway_from, gateway_to));
}

void EdgeCosts::gateway_passed(const rgmap::Gateway& g, double seconds)
{
  auto& r = gateways_[g.id];
  if (std::isfinite(seconds) && seconds > 0) r.time = blend(r.time, seconds, options_.learning_rate);
  ++r.passes;
  r.failures_in_a_row = 0;
  r.closed_until = 0;
  // Lowered by a fixed amount when it could be passed, never below the door's base cost.
  if (g.cls == rgmap::GatewayClass::kDoor) r.extra = std::max(0.0, r.extra + options_.door_passed_time);
  ++changes_;
}

void EdgeCosts::gateway_failed(const rgmap::Gateway& g, double now_s)
{
  auto& r = gateways_[g.id];
  ++r.failures;
  // What can stay shut (a door, a narrow passage, a gateway of no known kind) stays closed twice
  // as long with every failure in a row. An opening as wide as a hallway (a crossing, a turn) is
  // held only by what passes through it (people, a cart): it is tried again after closed_retry_s
  // however often it failed, or a robot whose only way on it is waits for nothing.
  constexpr int kMaxDoublings = 5;
  const bool can_stay_shut = g.cls == rgmap::GatewayClass::kDoor || g.cls == rgmap::GatewayClass::kNarrowPassage ||
                             g.cls == rgmap::GatewayClass::kUnknown;
  const int doublings = can_stay_shut ? std::min(r.failures_in_a_row, kMaxDoublings) : 0;
  r.closed_until = now_s + options_.closed_retry_s * (1 << doublings);
  r.failed_at = now_s;
  ++r.failures_in_a_row;
  if (g.cls == rgmap::GatewayClass::kDoor) r.extra += options_.door_failed_time;
  ++changes_;
}

bool EdgeCosts::closed(int64_t gateway_id, double now_s, ClosedHold hold) const
{
  const auto it = gateways_.find(gateway_id);
  return it != gateways_.end() && held(it->second, now_s, hold);
}

void EdgeCosts::region_traversed(int64_t region, int64_t gateway_from, int64_t gateway_to, double seconds)
{
  if (gateway_from == 0 || gateway_to == 0 || gateway_from == gateway_to || !std::isfinite(seconds) || seconds <= 0)
    return;
  auto& t = region_times_[region_key(region, gateway_from, gateway_to)];
  t = blend(t, seconds, options_.learning_rate);
  ++changes_;
}

nlohmann::json EdgeCosts::to_json() const
{
  nlohmann::json j;
  j["gateways"] = nlohmann::json::array();
  for (const auto& [id, r] : gateways_) {
    j["gateways"].push_back({{"id", id}, {"time_s", r.time}, {"passes", r.passes}, {"failures", r.failures},
                             {"extra_s", r.extra}, {"closed_until_s", r.closed_until},
                             {"failures_in_a_row", r.failures_in_a_row}, {"failed_at_s", r.failed_at}});
  }
  j["regions"] = nlohmann::json::array();
  for (const auto& [key, t] : region_times_) {
    j["regions"].push_back(
        {{"region", std::get<0>(key)}, {"from_gateway", std::get<1>(key)}, {"to_gateway", std::get<2>(key)}, {"time_s", t}});
  }
  return j;
}

void EdgeCosts::from_json(const nlohmann::json& j)
{
  auto number = [](const nlohmann::json& o, const char* key, const std::string& where) {
    if (!o.contains(key) || !o[key].is_number()) throw std::invalid_argument(where + "." + key + ": expected a number");
    const double v = o[key].get<double>();
    if (!std::isfinite(v)) throw std::invalid_argument(where + "." + key + ": not finite");
    return v;
  };
  auto array = [&](const char* key) -> const nlohmann::json& {
    if (!j.is_object() || !j.contains(key) || !j[key].is_array())
      throw std::invalid_argument(std::string(key) + ": expected an array");
    return j[key];
  };
  std::map<int64_t, GatewayRecord> gateways;
  std::map<RegionKey, double> regions;
  const auto& gs = array("gateways");
  for (size_t i = 0; i < gs.size(); ++i) {
    const std::string where = "gateways[" + std::to_string(i) + "]";
    GatewayRecord r;
    const auto id = static_cast<int64_t>(number(gs[i], "id", where));
    r.time = std::max(0.0, number(gs[i], "time_s", where));
    r.passes = static_cast<int>(number(gs[i], "passes", where));
    r.failures = static_cast<int>(number(gs[i], "failures", where));
    r.extra = std::max(0.0, number(gs[i], "extra_s", where));
    r.closed_until = number(gs[i], "closed_until_s", where);
    r.failures_in_a_row = static_cast<int>(number(gs[i], "failures_in_a_row", where));
    // Saved before the base hold was kept: the whole hold counts as its base.
    r.failed_at = gs[i].contains("failed_at_s") ? number(gs[i], "failed_at_s", where) : r.closed_until;
    gateways[id] = r;
  }
  const auto& rs = array("regions");
  for (size_t i = 0; i < rs.size(); ++i) {
    const std::string where = "regions[" + std::to_string(i) + "]";
    const double t = number(rs[i], "time_s", where);
    if (t <= 0) throw std::invalid_argument(where + ".time_s: must be > 0");
    regions[region_key(static_cast<int64_t>(number(rs[i], "region", where)),
                       static_cast<int64_t>(number(rs[i], "from_gateway", where)),
                       static_cast<int64_t>(number(rs[i], "to_gateway", where)))] = t;
  }
  gateways_ = std::move(gateways);
  region_times_ = std::move(regions);
}

}  // namespace rgnav::planner
