// The RG kernel's gateway traversals (diss. 5.2, 6.1): a traversal event (the detector's, or a
// doorway of the line map the robot went through) finalises the region left and leads into the
// region beyond — known (through a known gateway or a known place) or new — and the same
// crossing reported twice, by the kernel and the detector or as a door and as a junction,
// changes nothing the second time. Part of RgKernel (rg_kernel.h).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "geometry/segment2.h"
#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/known_place.h"
#include "procs/rg_kernel/rg_kernel.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;
using rgmap::Gateway;
using rgmap::Region;

namespace {

// [m] a door's line this near a junction side's line lies in it (both are measured edges of the
// same opening: jamb edges and the free-space boundary, a few cm apart in the simulated worlds).
constexpr double kDoorOnSideTolerance = 0.3;

// A crossing left within 60 degrees of its first traversal's heading (or the reverse) joins the
// same pair of branches: the robot turns inside a junction, its reported heading is that of the
// moment the detector decided.
constexpr double kSameBranchCos = 0.5;

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

void RgKernel::walk_through_door(const Vector2d& from, const ScanInput& s)
{
  // The robot's last step went through a door the gateway detector did not report; the kernel
  // crosses it as the detector would have reported it.
  // - A known door (a line gateway) of the current region, to its far side: the detector reports
  //   a door it has crossed before only if it recognises it again, and often does not as the
  //   robot leaves a room (rooms' regions then run on along the hallway for tens of metres, up to
  //   the next gateway). The kernel knows the door and which side is whose.
  // - A doorway of the current region's line map that no gateway stands in yet: a door the
  //   detector missed altogether (issue 8: missed gateways merge rooms).
  const int64_t rid = map_.current_region;
  const Region* r = map_.region(rid);
  const Vector2d to = (s.map_from_base * s.base_from_laser).translation();
  if ((to - from).norm() > options_.build.doorways.max_width) return;   // a jump (a gap in the scans), not a step
  auto traversal = [&](rgmap::GatewayClass cls, const std::vector<Vector2d>& points, const Vector2d& heading) {
    GatewayEventInput e;
    e.utime = s.utime;
    e.scan_id = s.scan_id;
    e.kind = GatewayEventInput::Kind::kTraversed;
    e.track_id = -s.scan_id;   // no detector track: never matches an ENTERED time
    e.cls = cls;
    e.map_from_base = s.map_from_base;
    e.gateway_points = points;
    e.direction = std::atan2(heading.y(), heading.x());
    return e;
  };
  for (const auto& [id, g] : map_.gateways()) {
    if (!options_.door_exits) break;
    if (g.neutralized || g.gateway_points.size() != 2 || g.region_b == 0 || g.traversal_directions.empty()) continue;
    const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
    if (a == b || (a != rid && b != rid)) continue;
    const geometry::Pose2& map_from_a = map_.region(g.region_a)->map_from_region;
    const Vector2d p = map_from_a * g.gateway_points[0], q = map_from_a * g.gateway_points[1];
    if (!geometry::segments_cross(from, to, p, q)) continue;
    const Vector2d beyond = (rid == a ? 1.0 : -1.0) * line_normal_to_b(g);   // towards the other region
    if (beyond.dot(to - from) <= 0) continue;   // stepped back in from the far side
    spdlog::info("region {}: the robot went back through gateway {} (unreported)", rid, id);
    add_gateway_event(traversal(g.cls, {p, q}, beyond));
    return;
  }
  const geometry::Pose2 region_from_map = r->map_from_region.inverse();
  if (options_.stem_exits && options_.stem_ends_branch && options_.min_branch_width > 0) {
    // - The stem side of a T-junction the current region lies beyond, into the junction: the
    //   region ends at that side (stem_ends_branch), so the robot has left it for the hallway's
    //   square, though a robot leaving a shallow room or bay cuts the junction's corner and the
    //   detector reports nothing (a row of cubicles: their regions then run on along the hallway
    //   up to the next cubicle). Like a door, a stem has two sides and no choice of branch: the
    //   crossing leads back into the region the gateway joins the current one to.
    // Per scan: the stems (line map, every robot position) are worked out only for a junction
    // of this region whose outline the step crosses.
    const RegionBuilder& builder = builders_.at(rid);
    std::vector<Vector2d> origins;
    const Vector2d f = region_from_map * from, t = region_from_map * to;
    const OpeningTest opening{options_.min_branch_width, options_.branch_wall_tolerance};
    for (const auto& [id, g] : map_.gateways()) {
      if (g.neutralized || g.gateway_points.size() != 4 || g.region_b == 0 || g.traversal_directions.empty()) continue;
      const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
      if (a == b || (a != rid && b != rid)) continue;
      const geometry::Pose2& map_from_a = map_.region(g.region_a)->map_from_region;
      std::vector<Vector2d> outline, in_map;
      for (const auto& p : g.gateway_points) {
        in_map.push_back(map_from_a * p);
        outline.push_back(region_from_map * in_map.back());
      }
      const auto sides = gateway_edges(outline);
      if (std::none_of(sides.begin(), sides.end(), [&](const Line& l) { return geometry::segments_cross(f, t, l.first, l.second); })) continue;
      if (origins.empty()) origins = builder.laser_origins();
      for (const StemSide& stem : stems_entered(outline, origins, side_reach(), builder.segments(), opening)) {
        if (!geometry::segments_cross(f, t, stem.side.line.first, stem.side.line.second)) continue;
        if (stem.side.normal.dot(t - f) >= 0) continue;   // out of the junction into the region
        const double a_to_b = g.traversal_directions.front() + map_from_a.theta();
        const double heading = rid == a ? a_to_b : a_to_b + M_PI;   // the way that leads to the other region
        spdlog::info("region {}: the robot left it through the stem of junction gateway {} (unreported)", rid, id);
        add_gateway_event(traversal(g.cls, in_map, Vector2d(std::cos(heading), std::sin(heading))));
        return;
      }
    }
  }
  if (!options_.doorway_gateways) return;
  const auto door =
      doorway_stepped_through(builders_.at(rid).segments(), region_from_map * from, region_from_map * to, options_.build.doorways);
  if (!door) return;
  const Vector2d p = r->map_from_region * door->first, q = r->map_from_region * door->second;
  for (const auto& [id, g] : map_.gateways())
    if (!g.neutralized && (crossing_in_map(g) - 0.5 * (p + q)).norm() < options_.gateway_match_distance) return;
  spdlog::info("region {}: the robot went through a doorway of its line map from ({:.2f}, {:.2f}) to ({:.2f}, {:.2f})", rid,
               p.x(), p.y(), q.x(), q.y());
  add_gateway_event(traversal(rgmap::GatewayClass::kNarrowPassage, {p, q}, to - from));
}

bool RgKernel::repeats_entry(const Gateway& g, int64_t current, double direction) const
{
  // A gateway crossed in the direction that leads into the current region does not lead out of
  // it: the same crossing reported a second time (the kernel's doorway and then the detector's
  // late event, or two detector tracks of one junction).
  if (g.traversal_directions.empty() || g.region_b == 0) return false;
  const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
  if (a == b || (current != a && current != b)) return false;
  if (g.gateway_points.size() == 4) {
    // A crossing: along the pair of branches its first traversal took, into the current one.
    const double a_to_b = g.traversal_directions.front() + map_.region(g.region_a)->map_from_region.theta();
    return std::cos(direction - (current == b ? a_to_b : a_to_b + M_PI)) >= kSameBranchCos;
  }
  if (g.gateway_points.size() != 2) return false;
  // Which side a heading leads to is the sign of its component along the line's normal (a
  // robot turning right after the door reports it 60 degrees off its first traversal's heading).
  const double into_b = line_normal_to_b(g).dot(Vector2d(std::cos(direction), std::sin(direction)));
  return current == b ? into_b > 0 : into_b < 0;
}

Vector2d RgKernel::line_normal_to_b(const Gateway& g) const
{
  const geometry::Pose2& map_from_a = map_.region(g.region_a)->map_from_region;
  const Vector2d along = map_from_a.rotation() * (g.gateway_points[1] - g.gateway_points[0]);
  Vector2d n = Vector2d(-along.y(), along.x()).normalized();
  const double a_to_b = g.traversal_directions.front() + map_from_a.theta();
  if (n.dot(Vector2d(std::cos(a_to_b), std::sin(a_to_b))) < 0) n = -n;
  return n;
}

int64_t RgKernel::leads_to(const Gateway& g, int64_t current, double direction) const
{
  // A line has two sides: crossed from one of its regions it leads to the other; crossed from
  // neither, to the side the crossing heads to (its first traversal led from region_a to
  // region_b). An outline joins its two regions only between the branches its first traversal
  // took: crossed in another heading it leads elsewhere (0).
  if (g.region_b == 0 || g.traversal_directions.empty()) return 0;
  const int64_t a = map_.resolve(g.region_a), b = map_.resolve(g.region_b);
  const double a_to_b = g.traversal_directions.front() + map_.region(g.region_a)->map_from_region.theta();
  if (g.gateway_points.size() != 4) {
    if (a == current) return b;
    if (b == current) return a;
    if (g.gateway_points.size() != 2) return a;
    return line_normal_to_b(g).dot(Vector2d(std::cos(direction), std::sin(direction))) > 0 ? b : a;
  }
  if (a == current && std::cos(direction - a_to_b) >= kSameBranchCos) return b;
  if (b == current && std::cos(direction - a_to_b - M_PI) >= kSameBranchCos) return a;
  return 0;
}

int64_t RgKernel::door_on_junction_side(const GatewayEventInput& e, int64_t current) const
{
  // A junction (an outline) the robot went in or out of through a door of the current region
  // that it crossed just now: the detector took the door in the hallway wall for a junction's
  // branch, and this is the same crossing reported a second time (the door's own report, the
  // kernel's doorway or the detector's, came first). As a gateway it would cut the hallway, or
  // the room, in two at a place no wall narrows.
  if (e.gateway_points.size() != 4) return 0;
  const Vector2d robot = e.map_from_base.translation();
  for (const auto& [id, d] : map_.gateways()) {
    if (d.neutralized || d.gateway_points.size() != 2 || d.region_b == 0) continue;
    if (map_.resolve(d.region_a) != current && map_.resolve(d.region_b) != current) continue;
    const geometry::Pose2& map_from_a = map_.region(d.region_a)->map_from_region;
    const Vector2d p = map_from_a * d.gateway_points[0], q = map_from_a * d.gateway_points[1];
    if ((0.5 * (p + q) - robot).norm() > options_.late_scan_reach) continue;
    if (line_on_crossed_side(e.gateway_points, p, q, e.direction, kDoorOnSideTolerance)) return id;
  }
  return 0;
}

std::vector<int64_t> RgKernel::scans_past_gateway(int64_t region_id, const GatewayEventInput& e) const
{
  // The detector reports a traversal once the robot is through (0.3-1.6 m in the simulated
  // worlds), so the region's newest scans were taken beyond the gateway. Left here, their
  // beams (not crossing the gateway line: they start beyond it) would carve the next room
  // into this region's freespace. The trailing run of such scans is handed on; the region
  // keeps at least its oldest scan.
  const std::vector<int64_t> by_time = builders_.at(region_id).scan_ids_by_time();
  std::vector<int64_t> late;   // newest first
  for (size_t i = by_time.size(); i-- > 1;) {
    const ScanInput& s = scan_inputs_.at(by_time[i]);
    const Vector2d p = (s.map_from_base * s.base_from_laser).translation();
    if (!past_gateway(p, e.gateway_points, e.direction, options_.late_scan_reach)) break;
    late.push_back(by_time[i]);
  }
  return late;
}

NarrowingProfile RgKernel::narrowing_of(const GatewayEventInput& e, int64_t current) const
{
  const geometry::Pose2 region_from_map = map_.region(current)->map_from_region.inverse();
  const Vector2d heading = region_from_map.rotation() * Vector2d(std::cos(e.direction), std::sin(e.direction));
  return narrowing_profile(region_from_map * e.gateway_points[0], region_from_map * e.gateway_points[1], heading,
                           builders_.at(current).segments(), options_.narrowing);
}

bool RgKernel::add_gateway_event(const GatewayEventInput& e)
{
  map_.utime = std::max(map_.utime, e.utime);
  if (e.kind == GatewayEventInput::Kind::kEntered) {
    entered_utime_[e.track_id] = e.utime;
    return false;
  }
  return traverse(e, {}, 0);
}

bool RgKernel::traverse(const GatewayEventInput& e, const std::vector<int64_t>& handed_on, int64_t into)
{
  if (e.kind != GatewayEventInput::Kind::kTraversed || map_.current_region == 0 || e.gateway_points.empty()) return false;

  const int64_t from = map_.current_region;
  Region* cur = map_.region(from);
  spdlog::debug("traversal event: class {} robot ({:.2f}, {:.2f}) heading {:.0f} deg, {} points, in region {}",
                rgmap::to_string(e.cls), e.map_from_base.x(), e.map_from_base.y(), e.direction * 180 / M_PI,
                e.gateway_points.size(), from);
  Vector2d c_map = Vector2d::Zero();
  for (const auto& p : e.gateway_points) c_map += p;
  c_map /= static_cast<double>(e.gateway_points.size());

  // A gateway we know already (crossed before, from either side)? A crossing joins more than
  // two regions, one gateway per pair: the one that leads on from here in this heading.
  std::vector<Gateway*> known;
  for (const auto& [id, k] : map_.gateways())
    if (!k.neutralized && (crossing_in_map(k) - c_map).norm() < options_.gateway_match_distance) known.push_back(map_.gateway(id));
  Gateway* g = nullptr;
  int64_t next = 0;
  for (Gateway* k : known) {
    if (repeats_entry(*k, from, e.direction)) {
      spdlog::info("gateway {}: traversal into region {} reported again, ignored", k->id, from);
      return false;
    }
    if (const int64_t n = leads_to(*k, from, e.direction)) {
      g = k;
      next = n;
      break;
    }
  }
  if (known.empty()) {
    if (const int64_t door = door_on_junction_side(e, from)) {
      spdlog::info("junction traversal at ({:.2f}, {:.2f}) is gateway {} crossed again (a door in its side), ignored",
                   c_map.x(), c_map.y(), door);
      return false;
    }
    if (e.gateway_points.size() == 2) {
      const NarrowingProfile n = narrowing_of(e, from);
      if (!n.narrowing) {
        // Quietly for the kernel's own lines (track_id < 0): its step into a known place
        // (entry_min_scans) is tried again at every scan.
        spdlog::log(e.track_id < 0 ? spdlog::level::debug : spdlog::level::info,
                    "{} traversal at ({:.2f}, {:.2f}) is no narrowing ({:.2f} m wide, {:.2f} m before, {:.2f} m after), "
                    "ignored", rgmap::to_string(e.cls), c_map.x(), c_map.y(), n.width, n.before, n.after);
        return false;
      }
    }
    if (walled_crossing(e, from)) {
      spdlog::info("{} traversal at ({:.2f}, {:.2f}) between walls (no branch-wide opening in its sides), ignored",
                   rgmap::to_string(e.cls), c_map.x(), c_map.y());
      return false;
    }
  }
  for (Gateway* k : known) {
    if (g || k->region_b != 0) continue;
    g = k;
    if (map_.resolve(k->region_a) == from) continue;   // ours, not traversed yet: connected below
    // Crossing a dangling gateway of another region from its far side: we are its region_b.
    next = map_.resolve(k->region_a);
    map_.connect(k->id, from, map_.region(k->region_a)->map_from_region.inverse() * cur->map_from_region);
  }
  if (!g) {
    // A new gateway, or a known crossing left into a branch none of its gateways leads to from
    // here: a gateway of its own between this region and the one beyond (same outline).
    const geometry::Pose2 region_from_map = cur->map_from_region.inverse();
    std::vector<Vector2d> points = e.gateway_points;
    rgmap::GatewayClass cls = e.cls;
    if (!known.empty()) {
      const Gateway& k = *known.front();
      const geometry::Pose2 map_from_k = map_.region(k.region_a)->map_from_region;
      points.clear();
      for (const auto& p : k.gateway_points) points.push_back(map_from_k * p);
      cls = k.cls;
    }
    Gateway& fresh = map_.add_gateway(cls, from, e.utime);
    for (const auto& p : points) fresh.gateway_points.push_back(region_from_map * p);
    fresh.crossing_points.push_back(region_from_map * c_map);
    fresh.traversal_directions.push_back(geometry::normalize_angle(e.direction - cur->map_from_region.theta()));
    g = &fresh;
    if (known.empty()) {
      spdlog::info("gateway {} ({}) found leaving region {}", fresh.id, rgmap::to_string(cls), from);
      mark_regions_behind(fresh);
    } else {
      const Gateway& k = *known.front();
      const double first = k.traversal_directions.empty()
                               ? 0.0
                               : k.traversal_directions.front() + map_.region(k.region_a)->map_from_region.theta();
      spdlog::info("gateway {} ({}): crossing of gateway {} (regions {}, {}; first heading {:.0f} deg) left from region {} "
                   "heading {:.0f} deg into another branch",
                   fresh.id, rgmap::to_string(cls), k.id, k.region_a, k.region_b,
                   geometry::normalize_angle(first) * 180 / M_PI, from, e.direction * 180 / M_PI);
    }
  }
  // Both are trailing runs of the region's scans (RegionBuilder::scan_ids_by_time): the longer holds the other.
  std::vector<int64_t> late = scans_past_gateway(from, e);   // newest first
  if (handed_on.size() > late.size()) late.assign(handed_on.rbegin(), handed_on.rend());
  for (const int64_t id : late) builders_.at(from).remove_scan(id);
  // Finalise the region we leave, now that its gateways (the new one too) filter its beams.
  if (progress_) progress_();
  describe(from, cur, true);
  if (progress_) progress_();
  dirty_.erase(from);
  cur->state = Region::State::kFinalised;
  cur->utime = e.utime;

  if (next == 0 && into != 0) next = into;
  if (next == 0) {
    // Past the gateway as the detector saw it just now, not only as it is known (another visit's
    // measurement, known_place.h).
    next = KnownPlaces(map_, builders_, from, options_.known_place, e.gateway_points)
               .region_holding(e.map_from_base.translation());
    if (next) spdlog::info("gateway {} leads from region {} into known region {}", g->id, from, next);
    if (progress_) progress_();
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

}  // namespace rgnav::rg_kernel
