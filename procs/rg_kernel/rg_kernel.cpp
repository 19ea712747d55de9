#include "procs/rg_kernel/rg_kernel.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/known_place.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;
using rgmap::Gateway;
using rgmap::Region;

namespace {

// True if the robot position p is through the gateway crossed with heading `heading`: beyond
// one of its lines that the crossing goes through (for a crossing's outline, a side whose
// outward normal points along the heading: the side it left by), less than `reach` from it and
// not beside its ends.
bool past_gateway(const Vector2d& p, const std::vector<Vector2d>& points, double heading, double reach)
{
  const Vector2d dir(std::cos(heading), std::sin(heading));
  for (EdgeFrame e : edge_frames(points)) {
    if (points.size() != 4 && e.normal.dot(dir) < 0) e.normal = -e.normal;  // a line: its side the crossing went to
    if (e.normal.dot(dir) < 0.5) continue;  // the crossing does not go out through this line
    if (e.just_beyond(p, reach)) return true;
  }
  return false;
}

}  // namespace

RgKernel::RgKernel(KernelOptions options) : options_(std::move(options)) {}

StoredScan RgKernel::to_stored(const ScanInput& s, int64_t region_id) const
{
  StoredScan out;
  out.scan_id = s.scan_id;
  out.utime = s.utime;
  out.revision = s.revision;
  out.region_from_laser = map_.region(region_id)->map_from_region.inverse() * s.map_from_base * s.base_from_laser;
  out.laser_points = s.laser_points;
  return out;
}

int64_t RgKernel::open_region(const geometry::Pose2& map_from_region, int64_t utime)
{
  Region& r = map_.add_region(map_from_region, utime);
  builders_.emplace(r.id, RegionBuilder(options_.build));
  spdlog::info("opened region {}", r.id);
  return r.id;
}

void RgKernel::enter(int64_t region_id, int64_t utime, const Vector2d& robot)
{
  Region* r = map_.region(region_id);
  r->state = Region::State::kOpen;
  r->utime = utime;
  map_.current_region = region_id;
  scans_since_entering_ = 0;
  builders_.at(region_id).set_gateway_lines(gateway_lines(region_id, &robot));
}

bool RgKernel::add_scan(const ScanInput& s)
{
  // A pose beyond any building (a corrupted or hostile input that is still finite) would make
  // the region's grids absurdly large: such a scan is refused, never stored or journaled twice.
  constexpr double kMaxCoordinate = 1e5;  // [m]
  if (std::fabs(s.map_from_base.x()) > kMaxCoordinate || std::fabs(s.map_from_base.y()) > kMaxCoordinate ||
      std::fabs(s.base_from_laser.x()) > 10 || std::fabs(s.base_from_laser.y()) > 10) {
    spdlog::warn("scan {} refused: pose outside +-{} m", s.scan_id, kMaxCoordinate);
    return false;
  }
  map_.utime = std::max(map_.utime, s.utime);
  auto known = region_of_scan_.find(s.scan_id);
  if (known != region_of_scan_.end()) {
    // A correction of an earlier scan (loop closure): re-place it in its region.
    if (s.revision <= scan_inputs_[s.scan_id].revision) return false;
    const int64_t rid = map_.resolve(known->second);
    scan_inputs_[s.scan_id] = s;
    builders_.at(rid).add_scan(to_stored(s, rid));
    dirty_.insert(rid);
    ++map_.version;
    return true;
  }
  if (map_.current_region == 0) {
    // The first region's frame is the first scan's robot pose.
    enter(open_region(s.map_from_base, s.utime), s.utime, s.map_from_base.translation());
  }
  const int64_t rid = map_.current_region;
  const std::vector<Vector2d> before = builders_.at(rid).laser_origins();
  builders_.at(rid).add_scan(to_stored(s, rid));
  region_of_scan_[s.scan_id] = rid;
  scan_inputs_[s.scan_id] = s;
  map_.last_scan_id = std::max(map_.last_scan_id, s.scan_id);
  map_.region(rid)->utime = s.utime;
  dirty_.insert(rid);
  ++scans_since_entering_;
  ++map_.version;
  if (!before.empty()) walk_through_doorway(map_.region(rid)->map_from_region * before.back(), s);
  maybe_merge_current(s.utime);
  return true;
}

void RgKernel::walk_through_doorway(const Vector2d& from, const ScanInput& s)
{
  // A doorway of the current region's line map that the robot's last step went through and that
  // no gateway stands in yet: a door the gateway detector missed (issue 8: missed gateways merge
  // rooms). The kernel crosses it as the detector would have reported it.
  if (!options_.doorway_gateways) return;
  const int64_t rid = map_.current_region;
  const Region* r = map_.region(rid);
  const geometry::Pose2 region_from_map = r->map_from_region.inverse();
  const Vector2d to = (s.map_from_base * s.base_from_laser).translation();
  const auto door =
      doorway_stepped_through(builders_.at(rid).segments(), region_from_map * from, region_from_map * to, options_.build.doorways);
  if (!door) return;
  const Vector2d p = r->map_from_region * door->first, q = r->map_from_region * door->second;
  for (const auto& [id, g] : map_.gateways())
    if (!g.neutralized && (crossing_in_map(g) - 0.5 * (p + q)).norm() < options_.gateway_match_distance) return;
  GatewayEventInput e;
  e.utime = s.utime;
  e.scan_id = s.scan_id;
  e.kind = GatewayEventInput::Kind::kTraversed;
  e.track_id = -s.scan_id;   // no detector track: never matches an ENTERED time
  e.cls = rgmap::GatewayClass::kNarrowPassage;
  e.map_from_base = s.map_from_base;
  e.gateway_points = {p, q};
  e.direction = std::atan2(to.y() - from.y(), to.x() - from.x());
  spdlog::info("region {}: the robot went through a doorway of its line map at ({:.2f}, {:.2f})", rid, 0.5 * (p.x() + q.x()),
               0.5 * (p.y() + q.y()));
  add_gateway_event(e);
}

Vector2d RgKernel::crossing_in_map(const Gateway& g) const
{
  const Region* a = map_.region(g.region_a);
  Vector2d c = Vector2d::Zero();
  if (!g.crossing_points.empty()) c = g.crossing_points.front();
  return a->map_from_region * c;
}

std::vector<std::pair<Vector2d, Vector2d>> RgKernel::gateway_lines(int64_t region_id, const Vector2d* robot) const
{
  // Every gateway of the map, not only the region's own: a hallway region's robot looks
  // through the open doors of rooms it never entered, and what lies beyond a door is the room
  // behind it once that door is a gateway (of whichever region found it).
  std::vector<std::pair<Vector2d, Vector2d>> lines;
  const Region* r = map_.region(region_id);
  std::vector<Vector2d> origins;
  if (auto b = builders_.find(region_id); b != builders_.end()) origins = b->second.laser_origins();
  if (robot) origins.push_back(r->map_from_region.inverse() * *robot);
  for (const auto& [id, g] : map_.gateways()) {
    if (g.neutralized || g.gateway_points.size() < 2) continue;
    const Region* a = map_.region(g.region_a);
    // Gateway points are stored in region_a's frame: move them into this region's frame.
    const geometry::Pose2 r_from_a = r->map_from_region.inverse() * a->map_from_region;
    std::vector<Vector2d> points;
    for (const auto& p : g.gateway_points) points.push_back(r_from_a * p);
    for (const auto& l : clip_lines(points, origins, options_.junction_side_reach, options_.gateway_line_extension)) lines.push_back(l);
  }
  return lines;
}

void RgKernel::mark_regions_behind(const Gateway& g)
{
  // A new gateway clips the beams of every region that saw past it: those whose freespace
  // reaches its points are described again (exactly, from all their beams) at the next refresh.
  const Region* a = map_.region(g.region_a);
  for (const auto& [id, b] : builders_) {
    const Region* r = map_.region(id);
    if (r->state != Region::State::kFinalised || r->freespace.width() == 0) continue;
    const geometry::Pose2 r_from_a = r->map_from_region.inverse() * a->map_from_region;
    for (const auto& p : g.gateway_points) {
      const Vector2d q = r_from_a * p;
      if (q.x() >= r->bbox_min.x() && q.y() >= r->bbox_min.y() && q.x() <= r->bbox_max.x() && q.y() <= r->bbox_max.y()) {
        dirty_.insert(id);
        break;
      }
    }
  }
}

bool RgKernel::repeats_entry(const Gateway& g, int64_t current, double direction) const
{
  // A door (a single line) crossed in the direction that leads into the current region does not
  // lead out of it: the same crossing reported a second time (the kernel's doorway and then the
  // detector's late event). Crossings (outlines) are left alone: they are left in many headings.
  if (g.gateway_points.size() != 2 || g.traversal_directions.empty() || g.region_b == 0) return false;
  const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
  if (a == b || (current != a && current != b)) return false;
  const double a_to_b = g.traversal_directions.front() + map_.region(g.region_a)->map_from_region.theta();
  const double into_current = current == b ? a_to_b : a_to_b + M_PI;
  return std::cos(direction - into_current) > 0.5;
}

std::vector<int64_t> RgKernel::scans_past_gateway(int64_t region_id, const GatewayEventInput& e) const
{
  // The detector reports a traversal once the robot is through (0.3-1.6 m in the simulated
  // worlds), so the region's newest scans were taken beyond the gateway. Left here, their
  // beams (not crossing the gateway line: they start beyond it) would carve the next room
  // into this region's freespace. The trailing run of such scans is handed on; the region
  // keeps at least its oldest scan.
  std::vector<std::pair<int64_t, int64_t>> by_time;   // (utime, scan id), newest first
  for (const auto& [id, s] : builders_.at(region_id).scans()) by_time.push_back({s.utime, id});
  std::sort(by_time.rbegin(), by_time.rend());
  std::vector<int64_t> late;
  for (size_t i = 0; i + 1 < by_time.size(); ++i) {
    const ScanInput& s = scan_inputs_.at(by_time[i].second);
    const Vector2d p = (s.map_from_base * s.base_from_laser).translation();
    if (!past_gateway(p, e.gateway_points, e.direction, options_.late_scan_reach)) break;
    late.push_back(by_time[i].second);
  }
  return late;
}

bool RgKernel::add_gateway_event(const GatewayEventInput& e)
{
  map_.utime = std::max(map_.utime, e.utime);
  if (e.kind == GatewayEventInput::Kind::kEntered) {
    entered_utime_[e.track_id] = e.utime;
    return false;
  }
  if (e.kind != GatewayEventInput::Kind::kTraversed || map_.current_region == 0 || e.gateway_points.empty()) return false;

  const int64_t from = map_.current_region;
  Region* cur = map_.region(from);
  Vector2d c_map = Vector2d::Zero();
  for (const auto& p : e.gateway_points) c_map += p;
  c_map /= static_cast<double>(e.gateway_points.size());

  // A gateway we know already (crossed before, from either side)?
  Gateway* g = nullptr;
  for (const auto& [id, known] : map_.gateways()) {
    if (!known.neutralized && (crossing_in_map(known) - c_map).norm() < options_.gateway_match_distance) {
      g = map_.gateway(id);
      break;
    }
  }
  int64_t next = 0;
  if (g && repeats_entry(*g, from, e.direction)) {
    spdlog::info("gateway {}: traversal into region {} reported again, ignored", g->id, from);
    return false;
  }
  if (g) {
    const int64_t a = map_.resolve(g->region_a), b = g->region_b ? map_.resolve(g->region_b) : 0;
    if (a == from) next = b;
    else if (b == from) next = a;
    else if (b == 0) {
      // Crossing a dangling gateway of another region from its far side: we are its region_b.
      map_.connect(g->id, from, map_.region(a)->map_from_region.inverse() * cur->map_from_region);
      next = a;
    } else {
      next = a;  // neither side is where we are: trust the gateway's geometry
    }
  } else {
    Gateway& fresh = map_.add_gateway(e.cls, from, e.utime);
    const geometry::Pose2 region_from_map = cur->map_from_region.inverse();
    for (const auto& p : e.gateway_points) fresh.gateway_points.push_back(region_from_map * p);
    fresh.crossing_points.push_back(region_from_map * c_map);
    fresh.traversal_directions.push_back(geometry::normalize_angle(e.direction - cur->map_from_region.theta()));
    g = &fresh;
    spdlog::info("gateway {} ({}) found leaving region {}", fresh.id, rgmap::to_string(e.cls), from);
    mark_regions_behind(fresh);
  }
  const std::vector<int64_t> late = scans_past_gateway(from, e);
  for (const int64_t id : late) builders_.at(from).remove_scan(id);
  // Finalise the region we leave, now that its gateways (the new one too) filter its beams.
  builders_.at(from).describe(cur, gateway_lines(from), true);
  dirty_.erase(from);
  cur->state = Region::State::kFinalised;
  cur->utime = e.utime;

  if (next == 0) {
    next = KnownPlaces(map_, builders_, from, options_.known_place).region_holding(e.map_from_base.translation());
    if (next) spdlog::info("gateway {} leads from region {} into known region {}", g->id, from, next);
  }
  if (next == 0) next = open_region(e.map_from_base, e.utime);
  if (g->region_b == 0 && map_.resolve(g->region_a) == from)
    map_.connect(g->id, next, map_.region(from)->map_from_region.inverse() * map_.region(next)->map_from_region);

  // Traversal statistics: the learned cost of this gateway (diss. 5.4).
  auto it = entered_utime_.find(e.track_id);
  if (it != entered_utime_.end() && e.utime > it->second) {
    const double t = (e.utime - it->second) * 1e-6;
    g->mean_traversal_time = (g->mean_traversal_time * g->traversals + t) / (g->traversals + 1);
    entered_utime_.erase(it);
  }
  ++g->traversals;
  enter(next, e.utime, e.map_from_base.translation());
  for (auto id = late.rbegin(); id != late.rend(); ++id) {
    builders_.at(next).add_scan(to_stored(scan_inputs_.at(*id), next));
    region_of_scan_[*id] = next;
  }
  if (!late.empty()) {
    scans_since_entering_ = static_cast<int>(late.size());
    dirty_.insert(next);
    spdlog::info("{} scan(s) taken past gateway {} moved from region {} to region {}", late.size(), g->id, from, next);
  }
  ++map_.version;
  return true;
}

void RgKernel::maybe_merge_current(int64_t utime)
{
  if (scans_since_entering_ < options_.merge_min_scans) return;
  const int64_t cur = map_.current_region;
  const auto origins = builders_.at(cur).laser_origins();
  const Region* r = map_.region(cur);
  const KnownPlaces known(map_, builders_, cur, options_.known_place);
  std::map<int64_t, int> inside;
  for (const auto& o : origins) {
    if (const int64_t q = known.region_holding(r->map_from_region * o)) ++inside[q];
  }
  for (const auto& [q, n] : inside) {
    if (n < options_.merge_inside_ratio * static_cast<double>(origins.size())) continue;
    // The current region is a place we know: merge it into q (diss. 6.1.1, Fig. 6.4).
    const geometry::Pose2 q_from_cur = map_.region(q)->map_from_region.inverse() * r->map_from_region;
    const int neutralized = map_.merge(cur, q, q_from_cur, utime);
    RegionBuilder& into = builders_.at(q);
    for (const auto& [sid, rid] : region_of_scan_) {
      if (rid != cur) continue;
      into.add_scan(to_stored(scan_inputs_.at(sid), q));
    }
    for (auto& [sid, rid] : region_of_scan_)
      if (rid == cur) rid = q;
    builders_.erase(cur);
    dirty_.erase(cur);
    dirty_.insert(q);
    spdlog::info("region {} is region {} seen again ({} of its {} robot positions seen from region {}'s): merged, {} "
                 "gateway(s) neutralized", cur, q, n, origins.size(), q, neutralized);
    enter(q, utime, r->map_from_region * origins.back());
    return;
  }
}

rgmap::Region RgKernel::describe_region(int64_t id) const
{
  Region r = *map_.region(id);
  auto it = builders_.find(id);
  if (it != builders_.end()) it->second.describe(&r, gateway_lines(id), r.state == Region::State::kFinalised);
  return r;
}

const rgmap::RgMap& RgKernel::refreshed_map()
{
  for (const int64_t id : dirty_) {
    const Region::State state = map_.region(id)->state;
    *map_.region(id) = describe_region(id);
    map_.region(id)->state = state;
  }
  dirty_.clear();
  return map_;
}

rgmap::RgMap RgKernel::described_map() const
{
  rgmap::RgMap m = map_;
  for (const auto& [id, b] : builders_) *m.region(id) = describe_region(id);
  return m;
}

std::vector<Vector2d> RgKernel::robot_positions(int64_t region_id) const
{
  std::vector<Vector2d> out;
  const auto b = builders_.find(region_id);
  if (b == builders_.end()) return out;
  const Region* r = map_.region(region_id);
  for (const auto& o : b->second.laser_origins()) out.push_back(r->map_from_region * o);
  return out;
}

KernelStats RgKernel::stats() const
{
  KernelStats s;
  for (const auto& [id, r] : map_.regions())
    if (r.state != Region::State::kMerged) ++s.regions;
  for (const auto& [id, g] : map_.gateways()) {
    ++s.gateways;
    if (g.neutralized) ++s.neutralized;
  }
  for (const auto& [id, b] : builders_) {
    s.segments += static_cast<int>(b.segments().size());
    s.raw_points += b.raw_points();
  }
  s.compression = s.segments > 0 ? static_cast<double>(s.raw_points) / (2.0 * s.segments) : 0.0;
  return s;
}

LineMapFidelity RgKernel::line_map_fidelity(double tolerance, double cap) const
{
  LineMapFidelity f;
  f.tolerance = tolerance;
  f.cap = cap;
  for (const auto& [id, b] : builders_) f.add(b.fidelity(tolerance, cap));
  return f;
}

}  // namespace rgnav::rg_kernel
