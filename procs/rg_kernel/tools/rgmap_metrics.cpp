#include "rgmap_metrics.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <unordered_map>
#include <utility>

namespace rgnav::rgmap_pipeline {

using Eigen::Vector2d;

int64_t min_segment_cells(const LabelGrid& grid)
{
  return std::max<int64_t>(1, std::llround(kMinSegmentArea / (grid.resolution * grid.resolution)));
}

RegionCells without_small_regions(const RegionCells& found, int64_t min_cells)
{
  RegionCells out;
  for (const auto& [id, cells] : found)
    if (static_cast<int64_t>(cells.size()) > min_cells) out.emplace(id, cells);
  return out;
}

LabelGrid without_small_rooms(LabelGrid grid, int64_t min_cells)
{
  std::map<int32_t, int64_t> size;
  for (int32_t l : grid.labels)
    if (l > 0) ++size[l];
  for (int32_t& l : grid.labels)
    if (l > 0 && size[l] <= min_cells) l = 0;
  return grid;
}

SegmentationScore score_segmentation(const LabelGrid& truth, const RegionCells& found, double split_share)
{
  SegmentationScore s;
  s.regions = static_cast<int>(found.size());
  std::map<int32_t, int64_t> room_cells, room_explored;
  for (int32_t l : truth.labels)
    if (l > 0) ++room_cells[l];
  s.rooms = static_cast<int>(room_cells.size());
  std::vector<char> covered(truth.labels.size(), 0);
  std::map<int64_t, std::map<int32_t, int64_t>> overlap;   // region -> room -> cells
  std::map<int64_t, int64_t> region_in_rooms;              // region -> its cells inside rooms
  for (const auto& [rid, cells] : found) {
    auto& ov = overlap[rid];
    for (int64_t c : cells) {
      if (c < 0 || c >= static_cast<int64_t>(truth.labels.size())) continue;
      const int32_t l = truth.labels[static_cast<size_t>(c)];
      if (l <= 0) continue;
      ++ov[l];
      ++region_in_rooms[rid];
      covered[static_cast<size_t>(c)] = 1;
    }
  }
  int64_t labelled = 0, covered_labelled = 0;
  for (size_t i = 0; i < truth.labels.size(); ++i) {
    if (truth.labels[i] <= 0) continue;
    ++labelled;
    if (covered[i]) {
      ++covered_labelled;
      ++room_explored[truth.labels[i]];
    }
  }
  s.coverage = labelled > 0 ? static_cast<double>(covered_labelled) / static_cast<double>(labelled) : 0.0;

  // Precision, best room and under-segmentation per region.
  double psum = 0;
  int pn = 0;
  for (const auto& [rid, ov] : overlap) {
    const int64_t total = region_in_rooms[rid];
    if (total == 0) {
      ++s.regions_outside;
      continue;
    }
    int32_t best = 0;
    int64_t best_n = -1;
    int big = 0;
    for (const auto& [room, n] : ov) {
      if (n > best_n) best = room, best_n = n;   // map order: ties go to the lower label
      if (static_cast<double>(n) >= split_share * static_cast<double>(total)) ++big;
    }
    s.region_to_room[rid] = best;
    psum += static_cast<double>(best_n) / static_cast<double>(total);
    ++pn;
    if (big >= 2) ++s.under_segmented;
  }
  s.precision = pn > 0 ? psum / pn : 0.0;

  // Recall, Jaccard and over-segmentation per room.
  double rsum = 0, rfull = 0, jsum = 0;
  for (const auto& [room, all] : room_cells) {
    const auto ex = room_explored.find(room);
    const int64_t explored = ex == room_explored.end() ? 0 : ex->second;
    int64_t best_n = 0;
    double best_iou = 0;
    int big = 0;
    for (const auto& [rid, ov] : overlap) {
      const auto it = ov.find(room);
      if (it == ov.end()) continue;
      const int64_t n = it->second;
      best_n = std::max(best_n, n);
      const double uni = static_cast<double>(region_in_rooms[rid] + explored - n);
      if (uni > 0) best_iou = std::max(best_iou, static_cast<double>(n) / uni);
      if (static_cast<double>(n) >= split_share * static_cast<double>(explored)) ++big;
    }
    rfull += static_cast<double>(best_n) / static_cast<double>(all);
    if (explored == 0) continue;
    ++s.rooms_explored;
    rsum += static_cast<double>(best_n) / static_cast<double>(explored);
    jsum += best_iou;
    if (big >= 2) ++s.over_segmented;
  }
  s.recall = s.rooms_explored > 0 ? rsum / s.rooms_explored : 0.0;
  s.jaccard = s.rooms_explored > 0 ? jsum / s.rooms_explored : 0.0;
  s.recall_full = s.rooms > 0 ? rfull / s.rooms : 0.0;
  return s;
}

GatewayMatch match_gateways(const std::vector<Vector2d>& truth, const std::vector<Vector2d>& found, double max_distance)
{
  GatewayMatch m;
  m.truth = static_cast<int>(truth.size());
  m.found = static_cast<int>(found.size());
  struct Pair
  {
    double d;
    int t, f;
  };
  std::vector<Pair> pairs;
  for (size_t t = 0; t < truth.size(); ++t)
    for (size_t f = 0; f < found.size(); ++f) {
      const double d = (truth[t] - found[f]).norm();
      if (d <= max_distance) pairs.push_back({d, static_cast<int>(t), static_cast<int>(f)});
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.d != b.d ? a.d < b.d : (a.t != b.t ? a.t < b.t : a.f < b.f);
  });
  std::vector<char> tu(truth.size(), 0), fu(found.size(), 0);
  double err = 0;
  for (const auto& p : pairs) {
    if (tu[static_cast<size_t>(p.t)] || fu[static_cast<size_t>(p.f)]) continue;
    tu[static_cast<size_t>(p.t)] = fu[static_cast<size_t>(p.f)] = 1;
    m.pairs.push_back({p.t, p.f});
    err += p.d;
  }
  std::sort(m.pairs.begin(), m.pairs.end());
  m.matched = static_cast<int>(m.pairs.size());
  m.missed = m.truth - m.matched;
  m.false_positives = m.found - m.matched;
  m.mean_error_m = m.matched > 0 ? err / m.matched : 0.0;
  return m;
}

namespace {

// Widens [lo, hi] to the corners of a region's freespace bitmap placed by world_from_region.
void add_freespace_extent(const rgmap::FreespaceBitmap& fs, const geometry::Pose2& world_from_region, Vector2d* lo,
                          Vector2d* hi)
{
  const geometry::Pose2 world_from_grid = world_from_region * fs.region_from_grid();
  for (const Vector2d& k : {Vector2d(0, 0), Vector2d(fs.width(), 0), Vector2d(0, fs.height()), Vector2d(fs.width(), fs.height())}) {
    const Vector2d p = world_from_grid * (k * fs.resolution());
    *lo = lo->cwiseMin(p);
    *hi = hi->cwiseMax(p);
  }
}

// Gateways of the map grouped by crossing: those with the same 4-point outline (within 1 cm in
// the map frame) in one group, lowest id first; every other gateway alone.
std::vector<std::vector<int64_t>> crossing_groups(const rgmap::RgMap& map)
{
  std::vector<std::pair<std::vector<Vector2d>, std::vector<int64_t>>> outlines;   // map frame
  std::vector<std::vector<int64_t>> out;
  for (const auto& [id, g] : map.gateways()) {
    const rgmap::Region* a = map.region(g.region_a);
    if (g.neutralized || g.gateway_points.size() != 4 || !a) {
      out.push_back({id});
      continue;
    }
    std::vector<Vector2d> pts;
    for (const auto& p : g.gateway_points) pts.push_back(a->map_from_region * p);
    auto same = std::find_if(outlines.begin(), outlines.end(), [&](const auto& o) {
      for (size_t k = 0; k < 4; ++k)
        if ((o.first[k] - pts[k]).norm() > 0.01) return false;
      return true;
    });
    if (same == outlines.end()) outlines.push_back({std::move(pts), {id}});
    else same->second.push_back(id);
  }
  for (auto& o : outlines) out.push_back(std::move(o.second));
  return out;
}

}  // namespace

Graph region_graph(const rgmap::RgMap& map)
{
  Graph g;
  for (const auto& [id, r] : map.regions())
    if (r.state != rgmap::Region::State::kMerged) g.nodes.insert(id);
  for (const auto& group : crossing_groups(map)) {
    std::set<int64_t> joined;
    for (int64_t id : group) {
      const rgmap::Gateway& gw = map.gateways().at(id);
      if (gw.neutralized || gw.region_a == 0 || gw.region_b == 0) continue;
      for (int64_t r : {map.resolve(gw.region_a), map.resolve(gw.region_b)})
        if (g.nodes.count(r)) joined.insert(r);
    }
    // A crossing joins every pair of the regions around it (the RG graph's gateway edges join
    // all its crossing points), however many pairs the robot went through.
    for (auto a = joined.begin(); a != joined.end(); ++a)
      for (auto b = std::next(a); b != joined.end(); ++b) g.add_edge(*a, *b);
  }
  return g;
}

std::set<int64_t> repeated_crossings(const rgmap::RgMap& map)
{
  std::set<int64_t> out;
  for (const auto& group : crossing_groups(map))
    for (size_t k = 1; k < group.size(); ++k) out.insert(group[k]);
  return out;
}

MapCounts count_map(const rgmap::RgMap& map, int64_t scan_points)
{
  MapCounts c;
  double bytes = 0, area = 0;
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) {
      ++c.merged;
      continue;
    }
    ++c.regions;
    c.segments += static_cast<int>(r.segments.size());
    bytes += static_cast<double>(r.freespace.bytes().size() + r.segments.size() * 4 * sizeof(float));
    area += r.freespace.features().area;
  }
  const std::set<int64_t> repeats = repeated_crossings(map);
  for (const auto& [id, g] : map.gateways()) {
    if (g.neutralized) {
      ++c.neutralized;
      continue;
    }
    if (repeats.count(id)) continue;
    ++c.gateways;
    if (g.cls == rgmap::GatewayClass::kDoor || g.cls == rgmap::GatewayClass::kNarrowPassage) ++c.doors;
    if (g.region_b == 0) ++c.not_traversed;
  }
  c.scan_points = scan_points;
  c.compression = c.segments > 0 ? static_cast<double>(scan_points) / (2.0 * c.segments) : 0.0;
  c.mean_region_bytes = c.regions > 0 ? bytes / c.regions : 0.0;
  c.mean_region_area_m2 = c.regions > 0 ? area / c.regions : 0.0;
  c.consistency_problems = static_cast<int>(map.consistency_problems().size());
  c.overlapping_regions = overlapping_region_pairs(map);
  return c;
}

int overlapping_region_pairs(const rgmap::RgMap& map, double share, double resolution)
{
  // A grid over every live region's freespace extent, in the map frame.
  Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& [id, r] : map.regions()) {
    const auto& fs = r.freespace;
    if (r.state != rgmap::Region::State::kMerged && fs.width() > 0 && fs.height() > 0)
      add_freespace_extent(fs, r.map_from_region, &lo, &hi);
  }
  if (lo.x() > hi.x()) return 0;
  const LabelGrid grid(static_cast<int>(std::ceil((hi.x() - lo.x()) / resolution)) + 1,
                       static_cast<int>(std::ceil((hi.y() - lo.y()) / resolution)) + 1, resolution, lo);
  const RegionCells cells = region_cells(map, geometry::Pose2(), grid);
  std::unordered_map<int64_t, std::vector<int64_t>> regions_of_cell;
  for (const auto& [id, cs] : cells)
    for (const int64_t c : cs) regions_of_cell[c].push_back(id);
  std::map<std::pair<int64_t, int64_t>, int> shared;
  for (const auto& [c, ids] : regions_of_cell)
    for (size_t i = 0; i < ids.size(); ++i)
      for (size_t j = i + 1; j < ids.size(); ++j) ++shared[{ids[i], ids[j]}];
  int pairs = 0;
  for (const auto& [ab, n] : shared) {
    const size_t smaller = std::min(cells.at(ab.first).size(), cells.at(ab.second).size());
    if (static_cast<double>(n) >= share * static_cast<double>(smaller)) ++pairs;
  }
  return pairs;
}

RegionCells region_cells(const rgmap::RgMap& map, const geometry::Pose2& world_from_map, const LabelGrid& grid)
{
  RegionCells out;
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    auto& cells = out[id];
    const auto& fs = r.freespace;
    if (fs.width() == 0 || fs.height() == 0) continue;
    const geometry::Pose2 world_from_region = world_from_map * r.map_from_region;
    Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    add_freespace_extent(fs, world_from_region, &lo, &hi);
    const geometry::Pose2 region_from_world = world_from_region.inverse();
    const int x0 = std::max(0, static_cast<int>(std::floor((lo.x() - grid.origin.x()) / grid.resolution)));
    const int y0 = std::max(0, static_cast<int>(std::floor((lo.y() - grid.origin.y()) / grid.resolution)));
    const int x1 = std::min(grid.width - 1, static_cast<int>(std::floor((hi.x() - grid.origin.x()) / grid.resolution)));
    const int y1 = std::min(grid.height - 1, static_cast<int>(std::floor((hi.y() - grid.origin.y()) / grid.resolution)));
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx)
        if (fs.is_free(region_from_world * grid.center(cx, cy))) cells.push_back(static_cast<int64_t>(cy) * grid.width + cx);
  }
  return out;
}

geometry::Pose2 fit_rigid(const std::vector<Vector2d>& a, const std::vector<Vector2d>& b)
{
  const size_t n = std::min(a.size(), b.size());
  if (n == 0) return {};
  Vector2d ma = Vector2d::Zero(), mb = Vector2d::Zero();
  for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= static_cast<double>(n);
  mb /= static_cast<double>(n);
  double sxx = 0, sxy = 0;   // sum of dot and cross products of the centred points
  for (size_t i = 0; i < n; ++i) {
    const Vector2d p = a[i] - ma, q = b[i] - mb;
    sxx += p.dot(q);
    sxy += p.x() * q.y() - p.y() * q.x();
  }
  const double theta = (sxx == 0 && sxy == 0) ? 0.0 : std::atan2(sxy, sxx);
  const geometry::Pose2 rot(0, 0, theta);
  const Vector2d t = mb - rot * ma;
  return geometry::Pose2(t, theta);
}

std::vector<Vector2d> gateway_positions(const rgmap::RgMap& map)
{
  std::vector<Vector2d> out;
  const std::set<int64_t> repeats = repeated_crossings(map);
  for (const auto& [id, g] : map.gateways()) {
    if (g.neutralized || repeats.count(id)) continue;
    const auto& pts = g.gateway_points.empty() ? g.crossing_points : g.gateway_points;
    const rgmap::Region* a = map.region(map.resolve(g.region_a));
    if (pts.empty() || !a) continue;
    Vector2d c = Vector2d::Zero();
    for (const auto& p : pts) c += p;
    out.push_back(a->map_from_region * (c / static_cast<double>(pts.size())));
  }
  return out;
}

}  // namespace rgnav::rgmap_pipeline
