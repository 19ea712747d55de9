#include "explorer/gateway_stack.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <stdexcept>

#include "explorer/frontiers.h"
#include "geometry/pose2.h"
#include "geometry/segment2.h"

namespace rgnav::explorer {

using Eigen::Vector2d;

namespace {

Vector2d unit(double heading) { return {std::cos(heading), std::sin(heading)}; }

// How far past an entry's crossing point the robot is through it. A door's or a passage's
// crossing point lies on its line: a step past it is through. A crossing's or a turn's lies in
// the middle of a square as wide as the hallway: a robot turning through the square into another
// branch, or stepping aside in it for a person, is that far along a branch it did not take (and
// the detector's estimate of the middle is off by as much); it has left by a branch only once it
// stands past the goal the explorer would send it to, beyond_m down that branch.
double through_distance(rgmap::GatewayClass cls, const StackOptions& o)
{
  switch (cls) {
    case rgmap::GatewayClass::kXCrossing:
    case rgmap::GatewayClass::kTCrossing:
    case rgmap::GatewayClass::kLTCrossing:
    case rgmap::GatewayClass::kRTCrossing:
    case rgmap::GatewayClass::kLTurn:
    case rgmap::GatewayClass::kRTurn: return o.beyond_m + o.passed_m;
    default: return o.passed_m;
  }
}

// RG-graph hops from `start` to every region it reaches through traversed gateways.
std::map<int64_t, int> hops_from(const rgmap::RgMap& map, int64_t start)
{
  std::map<int64_t, std::vector<int64_t>> next;
  for (const auto& [id, g] : map.gateways()) {
    if (g.neutralized || g.region_b == 0) continue;
    const int64_t a = map.resolve(g.region_a), b = map.resolve(g.region_b);
    if (a == b) continue;
    next[a].push_back(b);
    next[b].push_back(a);
  }
  std::map<int64_t, int> hops{{start, 0}};
  std::deque<int64_t> todo{start};
  while (!todo.empty()) {
    const int64_t r = todo.front();
    todo.pop_front();
    for (const int64_t n : next[r])
      if (hops.emplace(n, hops[r] + 1).second) todo.push_back(n);
  }
  return hops;
}

const char* state_name(StackEntry::State s)
{
  switch (s) {
    case StackEntry::State::kPending: return "pending";
    case StackEntry::State::kDone: return "done";
    case StackEntry::State::kSetAside: return "set_aside";
  }
  return "pending";
}

StackEntry::State state_from(const std::string& s)
{
  if (s == "pending") return StackEntry::State::kPending;
  if (s == "done") return StackEntry::State::kDone;
  if (s == "set_aside") return StackEntry::State::kSetAside;
  throw std::invalid_argument("stack entry state '" + s + "' is not pending, done or set_aside");
}

double finite(const nlohmann::json& j, const char* key)
{
  const double v = j.at(key).get<double>();
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(key) + " is not finite");
  return v;
}

}  // namespace

Vector2d StackEntry::beyond(double distance) const { return crossing + distance * unit(heading); }

void GatewayStack::add(const GatewaySighting& s, int64_t region_id, int64_t utime, const rgmap::RgMap& map)
{
  if (s.observations < options_.min_observations || !s.crossing.allFinite()) return;
  for (const double heading : s.headings) {
    if (!std::isfinite(heading)) continue;
    StackEntry* match = nullptr;
    for (auto& e : entries_) {
      if ((e.crossing - s.crossing).norm() > options_.merge_distance) continue;
      if (std::fabs(geometry::normalize_angle(e.heading - heading)) > options_.merge_angle) continue;
      match = &e;
      break;
    }
    if (match) {
      // The detector's estimate settles as the robot comes nearer: follow it while pending.
      if (match->state == StackEntry::State::kPending) match->crossing = 0.5 * (match->crossing + s.crossing);
      continue;
    }
    StackEntry e;
    e.id = next_id_;
    e.cls = s.cls;
    e.crossing = s.crossing;
    e.heading = geometry::normalize_angle(heading);
    e.region_id = region_id;
    e.utime = utime;
    // Into space the map already knows as free (back the way the robot came, or a region seen
    // from elsewhere): nothing to explore through it.
    if (known_free(map, e.beyond(options_.beyond_m))) continue;
    ++next_id_;
    entries_.push_back(e);
  }
}

int GatewayStack::update(const Vector2d& robot, const rgmap::RgMap& map)
{
  int marked = 0;
  for (auto& e : entries_) {
    if (e.state == StackEntry::State::kDone) continue;
    const Vector2d d = unit(e.heading);
    const Vector2d rel = robot - e.crossing;
    const double along = rel.dot(d), across = std::fabs(geometry::cross(d, rel));
    const double through = through_distance(e.cls, options_);
    if (along >= through && along <= std::max(through, options_.beyond_m) + 1.0 && across <= options_.merge_distance) {
      e.state = StackEntry::State::kDone;
      e.reason = "traversed";
      ++marked;
    } else if (known_free(map, e.beyond(options_.beyond_m), true) && known_free(map, e.beyond(2 * options_.beyond_m), true)) {
      // Seen from elsewhere: free in a region the robot has left (the open region's freespace
      // still takes in the branches of a crossing it has not gone through).
      e.state = StackEntry::State::kDone;
      e.reason = "seen beyond";
      ++marked;
    }
  }
  return marked;
}

std::vector<const StackEntry*> GatewayStack::order(const rgmap::RgMap& map, int64_t start_region, const Vector2d& robot,
                                                   int64_t utime) const
{
  const int64_t regions = static_cast<int64_t>(map.regions().size());
  std::vector<const StackEntry*> due;
  for (const auto& e : entries_) {
    if (e.state == StackEntry::State::kPending) due.push_back(&e);
    else if (e.state == StackEntry::State::kSetAside && e.retry_utime > 0 &&
             (utime >= e.retry_utime || regions > e.map_regions_at_failure))
      due.push_back(&e);
  }
  const std::map<int64_t, int> hops = hops_from(map, map.resolve(start_region));
  const auto level = [&](const StackEntry* e) {
    if (!options_.breadth_first) return 0;
    const auto it = hops.find(map.resolve(e->region_id));
    return it == hops.end() ? std::numeric_limits<int>::max() : it->second;
  };
  // Entries never tried before those that failed: a sighting the robot could not go through (a
  // gap between furniture, a corner taken for a door) is due again whenever the map gains a
  // region, and ahead of the rest by its level it would hold back every gateway seen since —
  // however far from the start the building's unexplored part lies.
  std::stable_sort(due.begin(), due.end(), [&](const StackEntry* a, const StackEntry* b) {
    const bool fa = a->state != StackEntry::State::kPending, fb = b->state != StackEntry::State::kPending;
    if (fa != fb) return fb;
    const int la = level(a), lb = level(b);
    if (la != lb) return la < lb;
    return (a->crossing - robot).squaredNorm() < (b->crossing - robot).squaredNorm();
  });
  return due;
}

void GatewayStack::done(int64_t id, const std::string& reason)
{
  for (auto& e : entries_)
    if (e.id == id) {
      e.state = StackEntry::State::kDone;
      e.reason = reason;
    }
}

void GatewayStack::failed(int64_t id, const std::string& reason, int64_t utime, int64_t retry_utime, int max_attempts,
                          int64_t map_regions, const PlaceView& view, bool counts, int max_closed_retries,
                          std::optional<LastFailure> from)
{
  for (auto& e : entries_) {
    if (e.id != id) continue;
    const bool closed = max_closed_retries > 0;
    if (closed) ++e.closed_failures;
    else if (counts) ++e.attempts;
    e.state = StackEntry::State::kSetAside;
    e.reason = reason;
    e.map_regions_at_failure = map_regions;
    e.failed_utime = utime;
    e.view_at_failure = view;
    e.failed_from = from;
    // For good after max_attempts: retry_utime 0 is never due (until release_changed).
    e.retry_utime = e.attempts >= max_attempts || (closed && e.closed_failures >= max_closed_retries) ? 0 : retry_utime;
  }
}

int GatewayStack::release_changed(const rgmap::RgMap& map, const PlaceViewOptions& o, int64_t utime,
                                  int64_t min_age_us, int max_attempts)
{
  int released = 0;
  for (auto& e : entries_) {
    if (e.state != StackEntry::State::kSetAside || e.retry_utime != 0 || utime - e.failed_utime < min_age_us) continue;
    if (!place_changed(e.view_at_failure, view_of_place(map, e.crossing, o), o)) continue;
    e.attempts = std::max(0, max_attempts - 1);
    e.retry_utime = utime;
    e.reason += " (the map near it changed: trying again)";
    ++released;
  }
  return released;
}

const StackEntry* GatewayStack::entry(int64_t id) const
{
  for (const auto& e : entries_)
    if (e.id == id) return &e;
  return nullptr;
}

int GatewayStack::count(StackEntry::State s) const
{
  return static_cast<int>(std::count_if(entries_.begin(), entries_.end(), [s](const StackEntry& e) { return e.state == s; }));
}

nlohmann::json GatewayStack::to_json() const
{
  nlohmann::json list = nlohmann::json::array();
  for (const auto& e : entries_) {
    list.push_back({{"id", e.id},
                    {"class", static_cast<int>(e.cls)},
                    {"crossing", {e.crossing.x(), e.crossing.y()}},
                    {"heading", e.heading},
                    {"region_id", e.region_id},
                    {"utime", e.utime},
                    {"state", state_name(e.state)},
                    {"attempts", e.attempts},
                    {"closed_failures", e.closed_failures},
                    {"retry_utime", e.retry_utime},
                    {"map_regions_at_failure", e.map_regions_at_failure},
                    {"failed_utime", e.failed_utime},
                    {"view_at_failure", place_view_json(e.view_at_failure)},
                    {"reason", e.reason}});
    if (e.failed_from) list.back()["failed_from"] = last_failure_json(*e.failed_from);
  }
  return {{"next_id", next_id_}, {"entries", list}};
}

void GatewayStack::from_json(const nlohmann::json& j)
{
  std::vector<StackEntry> entries;
  int64_t next_id = j.at("next_id").get<int64_t>();
  for (const auto& x : j.at("entries")) {
    StackEntry e;
    e.id = x.at("id").get<int64_t>();
    if (e.id <= 0 || e.id >= next_id) throw std::invalid_argument("stack entry id out of range");
    const int cls = x.at("class").get<int>();
    if (cls < 0 || cls > static_cast<int>(rgmap::GatewayClass::kOpening)) throw std::invalid_argument("stack entry class out of range");
    e.cls = static_cast<rgmap::GatewayClass>(cls);
    const auto& c = x.at("crossing");
    if (!c.is_array() || c.size() != 2) throw std::invalid_argument("stack entry crossing is not [x, y]");
    e.crossing = Vector2d(c[0].get<double>(), c[1].get<double>());
    if (!e.crossing.allFinite()) throw std::invalid_argument("stack entry crossing is not finite");
    e.heading = finite(x, "heading");
    e.region_id = x.at("region_id").get<int64_t>();
    e.utime = x.at("utime").get<int64_t>();
    e.state = state_from(x.at("state").get<std::string>());
    e.attempts = x.at("attempts").get<int>();
    // Absent in state files written before closed-gateway failures were bounded.
    e.closed_failures = x.value("closed_failures", 0);
    if (e.attempts < 0 || e.closed_failures < 0) throw std::invalid_argument("stack entry attempts or closed_failures < 0");
    e.retry_utime = x.at("retry_utime").get<int64_t>();
    e.map_regions_at_failure = x.at("map_regions_at_failure").get<int64_t>();
    // Absent in state files written before entries were released when the map near them changed.
    e.failed_utime = x.value("failed_utime", int64_t{0});
    if (x.contains("view_at_failure")) e.view_at_failure = place_view_from_json(x.at("view_at_failure"));
    // Absent in state files written before a failure was judged per goal.
    if (x.contains("failed_from")) e.failed_from = last_failure_from_json(x.at("failed_from"));
    e.reason = x.at("reason").get<std::string>();
    entries.push_back(e);
  }
  entries_ = std::move(entries);
  next_id_ = next_id;
}

}  // namespace rgnav::explorer
