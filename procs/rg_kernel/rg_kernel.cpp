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
  builders_.emplace(r.id, RegionBuilder(options_.build)).first->second.set_progress(progress_);
  spdlog::info("opened region {}", r.id);
  return r.id;
}

void RgKernel::set_progress(std::function<void()> progress)
{
  progress_ = std::move(progress);
  for (auto& [id, b] : builders_) b.set_progress(progress_);
}

void RgKernel::enter(int64_t region_id, int64_t utime, const Vector2d& robot)
{
  Region* r = map_.region(region_id);
  r->state = Region::State::kOpen;
  r->utime = utime;
  map_.current_region = region_id;
  scans_since_entering_ = 0;
  builders_.at(region_id).set_gateway_lines(beam_limits(region_id, &robot).lines);
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
  // What moved is seen through from beyond a gateway too: the other regions' points this scan
  // sees through leave their line maps (region_builder.h, seen_through_margin).
  for (auto& [q, b] : builders_) {
    if (q == rid) continue;
    const StoredScan in_q = to_stored(s, q);
    if (b.see_through_by(in_q.region_from_laser, in_q.laser_points)) dirty_.insert(q);
  }
  region_of_scan_[s.scan_id] = rid;
  scan_inputs_[s.scan_id] = s;
  map_.last_scan_id = std::max(map_.last_scan_id, s.scan_id);
  map_.region(rid)->utime = s.utime;
  dirty_.insert(rid);
  ++scans_since_entering_;
  ++map_.version;
  if (!before.empty()) walk_through_door(map_.region(rid)->map_from_region * before.back(), s);
  maybe_merge_current(s.utime);
  return true;
}

bool RgKernel::name_region(int64_t region_id, const std::string& name, std::string* why)
{
  const int64_t id = rgmap::region_to_name(map_, region_id, name, why);
  if (id == 0) return false;
  Region* r = map_.region(id);
  if (r->name == name) return false;
  spdlog::info("region {} named '{}'{}", id, name, r->name.empty() ? "" : " (was '" + r->name + "')");
  r->name = name;
  ++map_.version;
  return true;
}

bool RgKernel::add_objects3d(int64_t utime, const std::vector<rgmap::Rectangle3d>& in_map_frame)
{
  if (!options_.objects3d.enabled || in_map_frame.empty() || map_.current_region == 0) return false;
  Region* r = map_.region(map_.current_region);
  // Ids: region_id * 1000 + 500 + k, above the 2D objects' (object_grouping.h); never reused
  // within the region (the next one follows the highest kept).
  int64_t next_id = r->id * 1000 + 500;
  for (const auto& o : r->objects3d) next_id = std::max(next_id, o.id + 1);
  merge_objects3d(&r->objects3d, to_region_frame(in_map_frame, r->map_from_region), &next_id, options_.objects3d);
  r->utime = utime;
  ++map_.version;
  return true;
}

Vector2d RgKernel::crossing_in_map(const Gateway& g) const
{
  const Region* a = map_.region(g.region_a);
  Vector2d c = Vector2d::Zero();
  if (!g.crossing_points.empty()) c = g.crossing_points.front();
  return a->map_from_region * c;
}

BeamLimits RgKernel::beam_limits(int64_t region_id, const Vector2d* robot) const
{
  // Every gateway of the map, not only the region's own: a hallway region's robot looks
  // through the open doors of rooms it never entered, and what lies beyond a door is the room
  // behind it once that door is a gateway (of whichever region found it).
  BeamLimits out;
  const Region* r = map_.region(region_id);
  const geometry::Pose2 region_from_map = r->map_from_region.inverse();
  std::vector<Vector2d> origins;
  const std::vector<rgmap::LineSegment>* walls = nullptr;
  if (auto b = builders_.find(region_id); b != builders_.end()) {
    origins = b->second.laser_origins();
    walls = &b->second.segments();
  }
  if (robot) origins.push_back(region_from_map * *robot);
  const OpeningTest opening{options_.min_branch_width, options_.branch_wall_tolerance};
  const bool stems = options_.stem_ends_branch && options_.min_branch_width > 0 && walls;
  for (const auto& [id, g] : map_.gateways()) {
    if (g.neutralized || g.gateway_points.size() < 2) continue;
    // Gateway points are stored in region_a's frame: move them into this region's frame.
    const geometry::Pose2 r_from_a = region_from_map * map_.region(g.region_a)->map_from_region;
    std::vector<Vector2d> points;
    for (const auto& p : g.gateway_points) points.push_back(r_from_a * p);
    for (const auto& l : clip_lines(points, origins, side_reach(), options_.gateway_line_extension))
      out.lines.push_back(l);
    if (!stems || points.size() != 4) continue;
    // An X's branches end at their sides, but for the region the robot came from when it first
    // crossed the junction (the region_a of its first gateway): it keeps the square, as a
    // hallway keeps its crossing with another.
    const StemKind stem_kind =
        options_.x_branches_end && region_id != junction_owner(g) ? StemKind::kTOrX : StemKind::kT;
    // A stem side the region lies beyond (clip_lines opened it) ends its beams after all, lengthened
    // as a door is (the outline's side ends at the opening's measured edges, and beams grazing
    // past them carved wedges of hallway into cubicles along it), and its scans inside the
    // junction (as deep as the sides beside the stem are long) carve nothing.
    for (const StemSide& stem : stems_entered(points, origins, side_reach(), *walls, opening, stem_kind)) {
      out.lines.push_back(lengthened(stem.side.line, options_.gateway_line_extension));
      EdgeFrame inward = stem.side;
      inward.normal = -inward.normal;
      out.foreign.push_back({inward, stem.depth});
    }
  }
  // The region's own traversed lines (doors, narrow passages): the side its first traversal
  // headed to from region_a is region_b's (also while region_b is being opened), the other
  // region_a's.
  for (const auto& [id, g] : map_.gateways()) {
    if (g.neutralized || g.gateway_points.size() != 2 || g.traversal_directions.empty()) continue;
    const int64_t a = map_.resolve(g.region_a), b = g.region_b ? map_.resolve(g.region_b) : 0;
    if (a == b || (a != region_id && b != region_id)) continue;
    const geometry::Pose2 r_from_a = region_from_map * map_.region(g.region_a)->map_from_region;
    const double a_to_b = g.traversal_directions.front() + r_from_a.theta();
    const Vector2d beyond = (region_id == a ? 1.0 : -1.0) * Vector2d(std::cos(a_to_b), std::sin(a_to_b));
    for (EdgeFrame e : edge_frames({r_from_a * g.gateway_points[0], r_from_a * g.gateway_points[1]})) {
      if (e.normal.dot(beyond) < 0) e.normal = -e.normal;
      out.foreign.push_back({e, options_.late_scan_reach});
    }
  }
  return out;
}

int64_t RgKernel::junction_owner(const Gateway& g) const
{
  // The gateways of one crossing share its outline (a crossing joins more than two regions, one
  // gateway per pair); the map's ids are in creation order.
  const Vector2d c = crossing_in_map(g);
  for (const auto& [id, k] : map_.gateways()) {
    if (id >= g.id) break;
    if (!k.neutralized && k.gateway_points.size() == 4 && (crossing_in_map(k) - c).norm() < options_.gateway_match_distance)
      return map_.resolve(k.region_a);
  }
  return map_.resolve(g.region_a);
}

void RgKernel::describe(int64_t region_id, Region* region, bool exact) const
{
  const BeamLimits limits = beam_limits(region_id);
  builders_.at(region_id).describe(region, limits.lines, exact, limits.foreign);
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

void RgKernel::maybe_merge_current(int64_t utime)
{
  if (scans_since_entering_ < options_.merge_min_scans) return;
  const int64_t cur = map_.current_region;
  const auto origins = builders_.at(cur).laser_origins();
  const Region* r = map_.region(cur);
  const KnownPlaces known(map_, builders_, cur, options_.known_place);
  // Per known region: how many of all the positions, and of the recent ones, it holds.
  const size_t recent = std::min(origins.size(), static_cast<size_t>(options_.merge_recent_scans));
  std::map<int64_t, std::pair<int, int>> inside;
  std::vector<int64_t> holding(origins.size(), 0);
  std::vector<Vector2d> positions;   // map frame
  for (size_t i = 0; i < origins.size(); ++i) {
    positions.push_back(r->map_from_region * origins[i]);
    const int64_t q = holding[i] = known.region_holding(positions.back());
    if (q == 0) continue;
    ++inside[q].first;
    if (i >= origins.size() - recent) ++inside[q].second;
  }
  for (const auto& [q, counts] : inside) {
    const auto [n, n_recent] = counts;
    if (n < options_.merge_inside_ratio * static_cast<double>(origins.size()) ||
        n_recent < options_.merge_recent_ratio * static_cast<double>(recent))
      continue;
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
    spdlog::info("region {} is region {} seen again ({} of its {} robot positions, {} of the last {}, seen from region "
                 "{}'s): merged, {} gateway(s) neutralized", cur, q, n, origins.size(), n_recent, recent, q, neutralized);
    enter(q, utime, r->map_from_region * origins.back());
    return;
  }
  maybe_cross_into_known_place(positions, holding);
}

void RgKernel::maybe_cross_into_known_place(const std::vector<Vector2d>& positions, const std::vector<int64_t>& holding)
{
  if (options_.entry_min_scans <= 0 || holding.empty() || holding.back() == 0) return;
  const int64_t q = holding.back();
  size_t first = holding.size();   // of the newest run of positions in q
  while (first > 0 && holding[first - 1] == q) --first;
  const size_t run = holding.size() - first;
  if (run < static_cast<size_t>(options_.entry_min_scans) || first < static_cast<size_t>(options_.merge_min_scans)) return;
  // Before the run, a new place: mostly not q's (a region that is q seen again is merged instead).
  const auto in_q_before = std::count(holding.begin(), holding.begin() + static_cast<std::ptrdiff_t>(first), q);
  if (static_cast<double>(in_q_before) > (1.0 - options_.merge_inside_ratio) * static_cast<double>(first)) return;
  const Vector2d p0 = positions[first - 1], p1 = positions[first];
  if ((p1 - p0).norm() < 1e-6) return;
  const Vector2d mid = 0.5 * (p0 + p1);
  double depth = 0;
  for (size_t i = first; i < positions.size(); ++i) depth = std::max(depth, (positions[i] - mid).norm());
  if (depth < options_.entry_min_depth) return;
  // A line across the step, reaching to the walls of the region's line map on either side.
  const int64_t cur = map_.current_region;
  const RegionBuilder& b = builders_.at(cur);
  const Vector2d along = (p1 - p0).normalized(), across(-along.y(), along.x());
  const geometry::Pose2& map_from_cur = map_.region(cur)->map_from_region;
  auto reach = [&](const Vector2d& dir) {
    double best = options_.entry_max_half_width;
    for (const auto& seg : b.segments()) {
      const auto hit = ray_meets_line(mid, dir, map_from_cur * seg.a, map_from_cur * seg.b);
      if (hit && hit->along_ray > 0 && hit->along_ray < best && hit->along_line >= 0 && hit->along_line <= 1)
        best = hit->along_ray;
    }
    return best;
  };
  const std::vector<int64_t> scan_ids = b.scan_ids_by_time();   // as the positions are
  const ScanInput& in = scan_inputs_.at(scan_ids[first]);
  const ScanInput& now = scan_inputs_.at(scan_ids.back());
  GatewayEventInput e;
  e.utime = now.utime;
  e.scan_id = in.scan_id;
  e.kind = GatewayEventInput::Kind::kTraversed;
  e.track_id = -in.scan_id;   // no detector track
  e.cls = rgmap::GatewayClass::kUnknown;
  e.map_from_base = now.map_from_base;
  e.gateway_points = {mid + reach(across) * across, mid - reach(-across) * across};
  e.direction = std::atan2(along.y(), along.x());
  const std::vector<int64_t> handed_on(scan_ids.begin() + static_cast<std::ptrdiff_t>(first), scan_ids.end());
  // Logged after the traversal's own messages; a known gateway there the traversal repeats changes
  // nothing, and the next scan tries again (quietly).
  const bool crossed = traverse(e, handed_on, q);
  spdlog::log(crossed ? spdlog::level::info : spdlog::level::debug,
              "region {}: the robot had walked into known region {}'s place at ({:.2f}, {:.2f}) with no gateway between "
              "({} of its {} robot positions since){}", cur, q, mid.x(), mid.y(), run, holding.size(),
              crossed ? ": crossed there" : "; a known gateway there, nothing crossed");
}

rgmap::Region RgKernel::describe_region(int64_t id) const
{
  Region r = *map_.region(id);
  auto it = builders_.find(id);
  if (it != builders_.end()) describe(id, &r, r.state == Region::State::kFinalised);
  return r;
}

const rgmap::RgMap& RgKernel::refreshed_map(const std::function<void()>& between_regions)
{
  for (const int64_t id : dirty_) {
    const Region::State state = map_.region(id)->state;
    *map_.region(id) = describe_region(id);
    map_.region(id)->state = state;
    if (between_regions) between_regions();
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
