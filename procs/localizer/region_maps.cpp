#include "localizer/region_maps.h"

#include <cmath>
#include <limits>

#include "geometry/segment2.h"

namespace rgnav::localizer {

using Eigen::Vector2d;

double RegionModel::gateway_distance(const Vector2d& p, const RegionLink** nearest) const
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& link : links)
    for (const auto& [a, b] : link.lines) {
      const double d = geometry::point_segment_distance(p, a, b);
      if (d < best) {
        best = d;
        if (nearest) *nearest = &link;
      }
    }
  return best;
}

RegionMaps::RegionMaps(const ScanModel& scan, double seed_spacing) : scan_(scan), seed_spacing_(seed_spacing) {}

namespace {

// Freespace cell centres thinned to about `spacing` apart: where particles may be seeded.
std::vector<Vector2d> seed_positions(const rgmap::FreespaceBitmap& fs, double spacing)
{
  std::vector<Vector2d> out;
  if (fs.width() <= 0 || fs.resolution() <= 0) return out;
  const int step = std::max(1, static_cast<int>(std::lround(spacing / fs.resolution())));
  for (int cy = step / 2; cy < fs.height(); cy += step)
    for (int cx = step / 2; cx < fs.width(); cx += step)
      if (fs.free(cx, cy))
        out.push_back(fs.region_from_grid() * Vector2d((cx + 0.5) * fs.resolution(), (cy + 0.5) * fs.resolution()));
  return out;
}

// The part of the plane a region's field must cover: its freespace grown by the laser's reach
// (a stacked neighbour can be large; only what can be seen from this region matters).
std::pair<Vector2d, Vector2d> field_extent(const RegionModel& m)
{
  constexpr double kReach = 8.5;   // [m] LMS 2xx in its 8 m range mode, plus margin
  const auto& fs = m.freespace;
  Vector2d lo = Vector2d::Constant(1e300), hi = Vector2d::Constant(-1e300);
  for (const Vector2d c : {Vector2d(0, 0), Vector2d(fs.width(), 0), Vector2d(0, fs.height()), Vector2d(fs.width(), fs.height())}) {
    const Vector2d p = fs.region_from_grid() * (c * fs.resolution());
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo - Vector2d::Constant(kReach), hi + Vector2d::Constant(kReach)};
}

}  // namespace

void RegionMaps::set_map(const rgmap::RgMap& map)
{
  std::map<int64_t, std::shared_ptr<RegionModel>> next;
  merged_into_.clear();
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) {
      merged_into_[id] = r.merged_into;
      continue;
    }
    auto m = std::make_shared<RegionModel>();
    m->id = id;
    m->utime = r.utime;
    m->name = r.name;
    m->map_from_region = r.map_from_region;
    m->freespace = r.freespace;
    m->bbox_min = r.bbox_min;
    m->bbox_max = r.bbox_max;
    next[id] = m;
  }
  // Links: every traversed gateway that is not neutralized, seen from both of its regions.
  for (const auto& [gid, g] : map.gateways()) {
    if (g.neutralized || g.region_b == 0) continue;
    const int64_t a = map.resolve(g.region_a), b = map.resolve(g.region_b);
    if (a == b || !next.count(a) || !next.count(b)) continue;
    RegionLink ab{gid, b, g.region_a_from_region_b, {}};
    RegionLink ba{gid, a, g.region_a_from_region_b.inverse(), {}};
    for (const auto& [p, q] : rgmap::gateway_edges(g.gateway_points)) {
      ab.lines.emplace_back(p, q);
      ba.lines.emplace_back(ba.here_from_there * p, ba.here_from_there * q);
    }
    next[a]->links.push_back(std::move(ab));
    next[b]->links.push_back(std::move(ba));
  }
  // The stacked map of each region (diss. 5.3): its own lines and its neighbours' lines in its
  // frame, so that a robot near a gateway, whose beams reach into the next region, is weighed
  // against what it sees there. Rebuilt only when the region or a neighbour changed.
  for (auto& [id, m] : next) {
    m->stack_key = std::to_string(m->utime);
    for (const auto& l : m->links) m->stack_key += "|" + std::to_string(l.to) + ":" + std::to_string(map.region(l.to)->utime);
    const auto old = regions_.find(id);
    if (old != regions_.end() && old->second->stack_key == m->stack_key) {
      m->field = old->second->field;
      m->free_positions = old->second->free_positions;
      continue;
    }
    // Inside its bounding rectangle (its in-region measurements) a region's own lines are the
    // authority; a neighbour's lines only fill in what lies beyond it, seen through gateways.
    // (Where the two disagree, e.g. drift at a loop, a neighbour's copy of a wall would be a
    // ghost wall beside the own one.)
    const auto* own = map.region(id);
    const auto inside = [&](const Vector2d& p) {
      return p.x() > own->bbox_min.x() && p.y() > own->bbox_min.y() && p.x() < own->bbox_max.x() && p.y() < own->bbox_max.y();
    };
    std::vector<rgmap::LineSegment> stacked = own->segments;
    for (const auto& l : m->links)
      for (auto s : map.region(l.to)->segments) {
        s.a = l.here_from_there * s.a;
        s.b = l.here_from_there * s.b;
        if (inside(0.5 * (s.a + s.b))) continue;
        stacked.push_back(s);
      }
    m->field = LikelihoodField(stacked, scan_.field_resolution, scan_.max_distance, scan_.field_margin, field_extent(*m));
    m->free_positions = seed_positions(m->freespace, seed_spacing_);
  }
  regions_.clear();
  for (auto& [id, m] : next) regions_[id] = std::move(m);
  version_ = map.version;
}

const RegionModel* RegionMaps::region(int64_t id) const
{
  const auto it = regions_.find(id);
  return it == regions_.end() ? nullptr : it->second.get();
}

int64_t RegionMaps::resolve(int64_t id) const
{
  for (int guard = 0; guard < 64; ++guard) {
    if (regions_.count(id)) return id;
    const auto it = merged_into_.find(id);
    if (it == merged_into_.end()) return 0;
    id = it->second;
  }
  return 0;
}

int64_t RegionMaps::find_named(const std::string& name) const
{
  if (name.empty()) return 0;
  for (const auto& [id, r] : regions_)
    if (r->name == name) return id;
  return 0;
}

size_t RegionMaps::bytes() const
{
  size_t n = 0;
  for (const auto& [id, r] : regions_) n += r->field.bytes() + r->freespace.bytes().size() + r->free_positions.size() * sizeof(Vector2d);
  return n;
}

}  // namespace rgnav::localizer
