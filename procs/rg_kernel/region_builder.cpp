#include "procs/rg_kernel/region_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "procs/rg_kernel/freespace_trim.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

// [m] neighbouring end points farther apart than this are a depth jump: the free wedge between
// them reaches only as far as the nearer one.
constexpr double kMaxWedgeGap = 0.5;
// Seen-through test (seen_through.h): surfaces seen at a flatter incidence than 70 degrees are not
// tested (as the scan mapper's moving points); an open region's line map holding points seen
// through is rebuilt once it has grown by a quarter (and at least kRebuildMinScans scans) since
// its last rebuild: the rebuilds' cost is then a geometric series, a few builds of the region.
const double kMinCosIncidence = std::cos(70.0 * M_PI / 180.0);
constexpr double kRebuildGrowth = 0.25;
constexpr uint64_t kRebuildMinScans = 8;

uint64_t cell_key(int32_t x, int32_t y) { return (static_cast<uint64_t>(static_cast<uint32_t>(x)) << 32) | static_cast<uint32_t>(y); }
int32_t key_x(uint64_t k) { return static_cast<int32_t>(static_cast<uint32_t>(k >> 32)); }
int32_t key_y(uint64_t k) { return static_cast<int32_t>(static_cast<uint32_t>(k & 0xffffffffu)); }
// The index of the cell (side res) that coordinate v lies in.
int32_t cell_index(double v, double res) { return static_cast<int32_t>(std::floor(v / res)); }

// A beam that leaves the region through a gateway ends, for this region, at the gateway line:
// what lies beyond belongs to the next region (diss. 5.2 filters such beams; clipping keeps
// the free space in front of the gateway).
Vector2d clip_at_gateways(const Vector2d& o, const Vector2d& p, const RegionBuilder::GatewayLines& lines)
{
  Vector2d end = p;
  for (const auto& [a, b] : lines) {
    if (!geometry::segments_cross(o, end, a, b)) continue;
    const Vector2d d = end - o;
    // No parallel test: the two cross.
    end = o + d * geometry::ray_meets_line(o, d, a, b, 0.0)->along_ray;
  }
  return end;
}

// Cells whose centres lie in the triangle o, a, b: the free wedge between two neighbouring
// beams. Filling wedges rather than walking beams leaves no holes where beams diverge.
template <class F>
void for_cells_in_triangle(const Vector2d& o, const Vector2d& a, const Vector2d& b, double res, F f)
{
  const Vector2d lo = o.cwiseMin(a).cwiseMin(b), hi = o.cwiseMax(a).cwiseMax(b);
  auto side = [](const Vector2d& p, const Vector2d& q, const Vector2d& r) {
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
  };
  const double area = side(o, a, b);
  if (std::fabs(area) < 1e-12) return;
  for (int32_t y = cell_index(lo.y(), res); y <= cell_index(hi.y(), res); ++y) {
    for (int32_t x = cell_index(lo.x(), res); x <= cell_index(hi.x(), res); ++x) {
      const Vector2d c((x + 0.5) * res, (y + 0.5) * res);
      const double s1 = side(o, a, c), s2 = side(a, b, c), s3 = side(b, o, c);
      if (area > 0 ? (s1 >= 0 && s2 >= 0 && s3 >= 0) : (s1 <= 0 && s2 <= 0 && s3 <= 0)) f(x, y);
    }
  }
}

// Carves the free wedges of one scan (points in beam order, region frame) into `cells`:
// neighbouring in-range beams that do not cross a gateway bound a free triangle (cut at the
// nearer end point where they jump in depth); the end points' cells stay unmarked.
template <class F>
void carve_scan(const Vector2d& o, const std::vector<Vector2d>& pts, const std::vector<bool>& usable, double res,
                double max_gap, double robot_radius, F f)
{
  // Where the robot stood is free too (a forward-looking laser never sees its own position).
  const int32_t r = static_cast<int32_t>(std::ceil(robot_radius / res));
  const int32_t ox = cell_index(o.x(), res), oy = cell_index(o.y(), res);
  for (int32_t y = oy - r; y <= oy + r; ++y)
    for (int32_t x = ox - r; x <= ox + r; ++x)
      if ((Vector2d((x + 0.5) * res, (y + 0.5) * res) - o).norm() <= robot_radius) f(x, y);
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    if (!usable[i] || !usable[i + 1]) continue;
    const Vector2d da = pts[i] - o, db = pts[i + 1] - o;
    // Shrink the wedge by half a cell so the wall cells at its far edge are not marked free. At
    // a depth jump (an edge in front of something farther) both beams saw free space up to the
    // nearer end point, so the wedge is free that far: without it every jump would leave a thin
    // unknown sliver from the robot outward, and a planner that keeps off unknown space would
    // find the region cut into strips.
    double ra = da.norm(), rb = db.norm();
    if ((pts[i] - pts[i + 1]).norm() > max_gap) ra = rb = std::min(ra, rb);
    if (ra <= 0.5 * res || rb <= 0.5 * res) continue;
    const Vector2d a = o + da.normalized() * (ra - 0.5 * res);
    const Vector2d b = o + db.normalized() * (rb - 0.5 * res);
    for_cells_in_triangle(o, a, b, res, f);
  }
}

}  // namespace

void RegionBuilder::add_scan(StoredScan scan)
{
  auto it = scans_.find(scan.scan_id);
  if (it != scans_.end()) {
    if (scan.revision <= it->second.revision) return;  // old news (a duplicate or reordered message)
    it->second = std::move(scan);
    seen_scans_.erase(it->first);
    stale_ = true;
    seen_through_valid_ = false;
    return;
  }
  if (seen_through_valid_) see_through(scan);   // else all afresh at the rebuild
  if (!stale_) add_incrementally(scan);
  scans_.emplace(scan.scan_id, std::move(scan));
}

void RegionBuilder::remove_scan(int64_t scan_id)
{
  if (scans_.erase(scan_id) == 0) return;
  circle_observations_.erase(scan_id);
  seen_elsewhere_.erase(scan_id);
  stale_ = true;
  seen_through_valid_ = false;
}

const RegionBuilder::SeenScan& RegionBuilder::seen_scan(const StoredScan& scan) const
{
  auto it = seen_scans_.find(scan.scan_id);
  if (it != seen_scans_.end()) return it->second;
  std::vector<Vector2d> pts;
  pts.reserve(scan.laser_points.size());
  for (const auto& lp : scan.laser_points) pts.push_back(scan.region_from_laser * lp);
  auto normals = point_normals(pts, options_.extract.max_point_gap);
  Vector2d lo = scan.region_from_laser.translation(), hi = lo;
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  BeamView view(scan.region_from_laser, scan.laser_points, options_.freespace_max_range);
  const double reach = view.reach();
  return seen_scans_.emplace(scan.scan_id, SeenScan{std::move(view), std::move(pts), std::move(normals), reach, lo, hi})
      .first->second;
}

bool RegionBuilder::may_meet(const SeenScan& points, const SeenScan& beams)
{
  // The nearest place of the points' box to the beams' origin, within the beams' reach.
  const Vector2d o = beams.view.origin();
  return (o.cwiseMax(points.lo).cwiseMin(points.hi) - o).squaredNorm() <= beams.reach * beams.reach;
}

bool RegionBuilder::see_through_by(const geometry::Pose2& region_from_laser, const std::vector<Vector2d>& laser_points)
{
  if (options_.seen_through_margin <= 0 || scans_.empty()) return false;
  const BeamView view(region_from_laser, laser_points, options_.freespace_max_range);
  const SeenScan theirs{view, {}, {}, view.reach()};
  bool any = false;
  for (const auto& [id, s] : scans_) {
    const SeenScan& mine = seen_scan(s);
    if (!may_meet(mine, theirs)) continue;   // none of its points within the other scan's reach
    const auto own = seen_through_.find(id);
    auto& flags = seen_elsewhere_[id];
    flags.resize(mine.points.size(), 0);
    for (size_t i = 0; i < mine.points.size(); ++i) {
      if (flags[i] || (own != seen_through_.end() && i < own->second.size() && own->second[i])) continue;
      if (!theirs.view.sees_through(mine.points[i], mine.normals[i], options_.seen_through_margin, kMinCosIncidence)) continue;
      flags[i] = 1;
      any = true;
    }
  }
  if (any) holds_seen_through_ = true;
  return any;
}

void RegionBuilder::see_through(const StoredScan& scan) const
{
  if (options_.seen_through_margin <= 0) return;
  const double margin = options_.seen_through_margin;
  const SeenScan& mine = seen_scan(scan);
  auto& flags = seen_through_[scan.scan_id];
  flags.assign(mine.points.size(), 0);
  for (const auto& [id, s] : scans_) {
    if (id == scan.scan_id) continue;
    const SeenScan& theirs = seen_scan(s);
    if (may_meet(mine, theirs))
      for (size_t i = 0; i < mine.points.size(); ++i)
        if (!flags[i] && theirs.view.sees_through(mine.points[i], mine.normals[i], margin, kMinCosIncidence)) flags[i] = 1;
    auto& their_flags = seen_through_[id];
    their_flags.resize(theirs.points.size(), 0);
    if (!may_meet(theirs, mine)) continue;
    for (size_t i = 0; i < theirs.points.size(); ++i)
      if (!their_flags[i] && mine.view.sees_through(theirs.points[i], theirs.normals[i], margin, kMinCosIncidence)) {
        their_flags[i] = 1;
        holds_seen_through_ = true;   // perhaps merged already (unless it was in free space then)
      }
  }
}

void RegionBuilder::see_through_all() const
{
  seen_through_.clear();
  seen_scans_.clear();
  seen_through_valid_ = true;
  if (options_.seen_through_margin <= 0) return;
  const double margin = options_.seen_through_margin;
  for (const auto& [id, s] : scans_) {
    note_progress();
    const SeenScan& mine = seen_scan(s);
    auto& flags = seen_through_[id];
    flags.assign(mine.points.size(), 0);
    for (const auto& [other, t] : scans_) {
      if (other == id || !may_meet(mine, seen_scan(t))) continue;
      const BeamView& v = seen_scan(t).view;
      for (size_t i = 0; i < mine.points.size(); ++i)
        if (!flags[i] && v.sees_through(mine.points[i], mine.normals[i], margin, kMinCosIncidence)) flags[i] = 1;
    }
  }
}

void RegionBuilder::rebuild_if_seen_through(bool exact) const
{
  if (!holds_seen_through_ || stale_) return;
  const uint64_t n = scans_.size();
  const double due = static_cast<double>(scans_at_rebuild_) * (1.0 + kRebuildGrowth);
  if (exact || (n >= scans_at_rebuild_ + kRebuildMinScans && static_cast<double>(n) >= due)) stale_ = true;
}

void RegionBuilder::add_incrementally(const StoredScan& scan) const
{
  add_lines(scan);
  carve(scan);
}

bool RegionBuilder::in_free_space(const Vector2d& p) const
{
  const double res = options_.freespace_resolution;
  const int32_t cx = cell_index(p.x(), res), cy = cell_index(p.y(), res);
  for (int32_t y = cy - 2; y <= cy + 2; ++y)
    for (int32_t x = cx - 2; x <= cx + 2; ++x)
      if (!free_cells_.count(cell_key(x, y))) return false;
  return true;
}

void RegionBuilder::add_lines(const StoredScan& scan) const
{
  const Vector2d o = scan.region_from_laser.translation();
  std::vector<Vector2d> pts;
  pts.reserve(scan.laser_points.size());
  const auto seen = seen_through_.find(scan.scan_id);
  const auto elsewhere = seen_elsewhere_.find(scan.scan_id);
  for (size_t i = 0; i < scan.laser_points.size(); ++i) {
    if (seen != seen_through_.end() && i < seen->second.size() && seen->second[i]) continue;
    if (elsewhere != seen_elsewhere_.end() && i < elsewhere->second.size() && elsewhere->second[i]) continue;
    const Vector2d p = scan.region_from_laser * scan.laser_points[i];
    if (!options_.drop_points_in_free_space || !in_free_space(p)) pts.push_back(p);
  }
  // Tolerances follow the scan's own range noise (line_map.h): coarse logs keep walls whole.
  const double noise = estimate_range_noise(pts, options_.extract.max_point_gap);
  const auto correction = align_to_line_map(pts, segments_, options_.align);
  segments_ = merge_into(std::move(segments_), extract_segments(pts, options_.extract, noise), options_.merge, noise,
                         correction ? &*correction : nullptr);
  auto circles = circles_in_scan({o, pts}, options_.objects);
  if (circles.empty()) circle_observations_.erase(scan.scan_id);
  else circle_observations_[scan.scan_id] = std::move(circles);
}

void RegionBuilder::carve(const StoredScan& scan) const
{
  const Vector2d o = scan.region_from_laser.translation();
  std::vector<Vector2d> pts;
  pts.reserve(scan.laser_points.size());
  for (const auto& lp : scan.laser_points) pts.push_back(scan.region_from_laser * lp);
  lo_ = lo_.cwiseMin(o);
  hi_ = hi_.cwiseMax(o);
  std::vector<bool> usable(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    pts[i] = clip_at_gateways(o, pts[i], gateway_lines_);
    usable[i] = (pts[i] - o).norm() <= options_.freespace_max_range;
    if (!usable[i]) continue;
    lo_ = lo_.cwiseMin(pts[i]);
    hi_ = hi_.cwiseMax(pts[i]);
  }
  carve_scan(o, pts, usable, options_.freespace_resolution, kMaxWedgeGap, options_.robot_radius,
             [&](int32_t x, int32_t y) { free_cells_.insert(cell_key(x, y)); });
}

void RegionBuilder::refresh() const
{
  if (!stale_) return;
  segments_.clear();
  free_cells_.clear();
  circle_observations_.clear();
  lo_ = Vector2d::Constant(std::numeric_limits<double>::max());
  hi_ = -lo_;
  // All the free space first, so that what moved is known wherever it was seen empty, at any time;
  // and every point any other scan saw through.
  for (const auto& [id, s] : scans_) {
    note_progress();
    carve(s);
  }
  if (!seen_through_valid_) see_through_all();
  for (const auto& [id, s] : scans_) {
    note_progress();
    add_lines(s);
  }
  stale_ = false;
  holds_seen_through_ = false;
  scans_at_rebuild_ = scans_.size();
}

const std::vector<rgmap::LineSegment>& RegionBuilder::segments() const
{
  rebuild_if_seen_through(false);
  refresh();
  return segments_;
}

int64_t RegionBuilder::raw_points() const
{
  int64_t n = 0;
  for (const auto& kv : scans_) n += static_cast<int64_t>(kv.second.laser_points.size());
  return n;
}

LineMapFidelity RegionBuilder::fidelity(double tolerance, double cap) const
{
  refresh();
  std::vector<Vector2d> pts;
  pts.reserve(static_cast<size_t>(raw_points()));
  for (const auto& [id, s] : scans_)
    for (const auto& lp : s.laser_points) pts.push_back(s.region_from_laser * lp);
  return measure_fidelity(pts, segments_, tolerance, cap);
}

std::vector<int64_t> RegionBuilder::scan_ids_by_time() const
{
  std::vector<std::pair<int64_t, int64_t>> by_time;   // (utime, id)
  for (const auto& [id, s] : scans_) by_time.push_back({s.utime, id});
  std::sort(by_time.begin(), by_time.end());
  std::vector<int64_t> out;
  for (const auto& e : by_time) out.push_back(e.second);
  return out;
}

std::vector<Vector2d> RegionBuilder::laser_origins() const
{
  std::vector<Vector2d> out;
  for (const int64_t id : scan_ids_by_time()) out.push_back(scans_.at(id).region_from_laser.translation());
  return out;
}

void RegionBuilder::describe(rgmap::Region* region, const GatewayLines& gateway_lines, bool exact,
                             const std::vector<ForeignSide>& foreign) const
{
  rebuild_if_seen_through(exact);
  refresh();
  region->segments = segments_;
  region->nscans = static_cast<int>(scans_.size());
  if (scans_.empty()) return;
  const double res = options_.freespace_resolution;
  if (!exact) {
    std::vector<std::pair<int32_t, int32_t>> cells;
    cells.reserve(free_cells_.size());
    for (const uint64_t k : free_cells_) cells.emplace_back(key_x(k), key_y(k));
    fill_region(region, lo_, hi_, cells);
    fill_objects(region);
    return;
  }
  // Exact: every beam again, with every gateway known now and the doorways of the line map.
  GatewayLines lines = gateway_lines;
  for (const auto& l : doorways_not_crossed(find_doorways(segments_, options_.doorways), laser_origins())) lines.push_back(l);
  std::unordered_set<uint64_t> cells_set;
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  auto on_foreign_side = [&](const StoredScan& s) {
    const Vector2d o = s.region_from_laser.translation();
    return std::any_of(foreign.begin(), foreign.end(), [&](const ForeignSide& f) { return f.edge.just_beyond(o, f.reach); });
  };
  // A region has its own space: if every scan stood beyond its gateways, the sides are wrong.
  const bool filter = std::any_of(scans_.begin(), scans_.end(), [&](const auto& kv) { return !on_foreign_side(kv.second); });
  std::vector<Cell> origins;   // of the scans carved: where the region's own space is (freespace_trim.h)
  for (const auto& [id, s] : scans_) {
    note_progress();
    if (filter && on_foreign_side(s)) continue;
    const Vector2d o = s.region_from_laser.translation();
    origins.emplace_back(cell_index(o.x(), res), cell_index(o.y(), res));
    lo = lo.cwiseMin(o);
    hi = hi.cwiseMax(o);
    std::vector<Vector2d> pts;
    std::vector<bool> usable;
    for (const auto& lp : s.laser_points) {
      const Vector2d p = clip_at_gateways(o, s.region_from_laser * lp, lines);
      pts.push_back(p);
      usable.push_back((p - o).norm() <= options_.freespace_max_range);
      if (!usable.back()) continue;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    carve_scan(o, pts, usable, res, kMaxWedgeGap, options_.robot_radius, [&](int32_t x, int32_t y) { cells_set.insert(cell_key(x, y)); });
  }
  std::vector<Cell> cells;
  for (const uint64_t k : cells_set) cells.emplace_back(key_x(k), key_y(k));
  if (options_.freespace_min_passage > 0)
    cells = trim_seen_through(cells, origins, cell_index(0.5 * options_.freespace_min_passage, res));
  fill_region(region, lo, hi, cells);
  fill_objects(region);
}

void RegionBuilder::fill_objects(rgmap::Region* region) const
{
  std::vector<CircleObservation> circles;
  for (const auto& [id, obs] : circle_observations_) circles.insert(circles.end(), obs.begin(), obs.end());
  region->objects = find_objects(region->id, segments_, circles, region->freespace, options_.objects);
}

void RegionBuilder::fill_region(rgmap::Region* region, const Vector2d& lo, const Vector2d& hi,
                                const std::vector<std::pair<int32_t, int32_t>>& cells) const
{
  if (lo.x() > hi.x()) return;
  region->bbox_min = lo;
  region->bbox_max = hi;
  const double res = options_.freespace_resolution;
  // The bitmap is aligned with the region frame's cell grid, so cell (x, y) maps exactly.
  const int32_t x0 = cell_index(lo.x(), res), y0 = cell_index(lo.y(), res);
  const int32_t x1 = cell_index(hi.x(), res), y1 = cell_index(hi.y(), res);
  // Bounded: at most 2000 x 2000 cells (300 m at 15 cm); a larger box means bad input.
  if (static_cast<int64_t>(x1) - x0 >= 2000 || static_cast<int64_t>(y1) - y0 >= 2000) return;
  rgmap::FreespaceBitmap fs(res, geometry::Pose2(x0 * res, y0 * res, 0.0), x1 - x0 + 1, y1 - y0 + 1);
  for (const auto& [x, y] : cells) fs.set_free(x - x0, y - y0, true);
  region->freespace = std::move(fs);
  // Completeness: observed (free) share of the bounding rectangle; accuracy: how tightly the
  // merged segments fit their points (1 at sigma 0, 0.5 at 2 cm).
  const double box = (hi.x() - lo.x()) * (hi.y() - lo.y());
  region->completeness = box > 0 ? std::min(1.0, region->freespace.free_cells() * res * res / box) : 0.0;
  double sum = 0, n = 0;
  for (const auto& s : segments_) {
    sum += s.sigma * s.support;
    n += s.support;
  }
  region->accuracy = n > 0 ? 1.0 / (1.0 + (sum / n) / 0.02) : 0.0;
}

}  // namespace rgnav::rg_kernel
