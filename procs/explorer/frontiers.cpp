#include "explorer/frontiers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/segment2.h"

namespace rgnav::explorer {

using Eigen::Vector2d;

namespace {

using Segment = std::pair<Vector2d, Vector2d>;

// Another live region and where it lies: the frame that takes this region's points into it.
struct OtherRegion
{
  const rgmap::Region* region = nullptr;
  geometry::Pose2 other_from_this;
};

double distance_to(const std::vector<Segment>& lines, const Vector2d& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : lines) best = std::min(best, geometry::point_segment_distance(p, a, b));
  return best;
}

// The lines of every traversed door-like gateway of region `rid` (either side), in its frame:
// the RG kernel ends both regions' freespace a little short of such a line, so the strip between
// them is no frontier. A crossing's outline is not among them: its other branches may lead
// where nobody has been (what lies in a neighbour's freespace is explained anyway).
std::vector<Segment> gateway_lines(const rgmap::RgMap& map, int64_t rid)
{
  std::vector<Segment> lines;
  for (const auto& [id, g] : map.gateways()) {
    if (g.neutralized || g.region_b == 0 || g.gateway_points.size() == 4) continue;
    geometry::Pose2 this_from_a;
    if (map.resolve(g.region_a) == rid) {
      this_from_a = geometry::Pose2();
    } else if (g.region_b != 0 && map.resolve(g.region_b) == rid) {
      this_from_a = g.region_a_from_region_b.inverse();
    } else {
      continue;
    }
    for (const auto& [a, b] : rgmap::gateway_edges(g.gateway_points)) lines.emplace_back(this_from_a * a, this_from_a * b);
  }
  return lines;
}

std::vector<OtherRegion> other_regions(const rgmap::RgMap& map, const rgmap::Region& self)
{
  std::vector<OtherRegion> others;
  const geometry::Pose2 map_from_this = self.map_from_region;
  for (const auto& [id, r] : map.regions()) {
    if (id == self.id || r.state == rgmap::Region::State::kMerged || r.freespace.width() == 0) continue;
    others.push_back({&r, r.map_from_region.inverse() * map_from_this});
  }
  return others;
}

}  // namespace

bool known_free(const rgmap::RgMap& map, const Vector2d& map_point, bool settled_only)
{
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged || r.freespace.width() == 0) continue;
    if (settled_only && r.state != rgmap::Region::State::kFinalised) continue;
    if (r.freespace.is_free(r.map_from_region.inverse() * map_point)) return true;
  }
  return false;
}

RegionFrontiers find_frontiers(const rgmap::RgMap& map, int64_t region_id, const FrontierOptions& options)
{
  RegionFrontiers out;
  const rgmap::Region* region = map.region(region_id);
  if (!region || region->state == rgmap::Region::State::kMerged) return out;
  const rgmap::FreespaceBitmap& fs = region->freespace;
  const int w = fs.width(), h = fs.height();
  if (w == 0 || h == 0) return out;
  const double res = fs.resolution();
  const auto centre = [&](int cx, int cy) { return fs.region_from_grid() * Vector2d((cx + 0.5) * res, (cy + 0.5) * res); };

  std::vector<Segment> walls;
  for (const auto& s : region->segments) walls.emplace_back(s.a, s.b);
  const std::vector<Segment> openings = gateway_lines(map, region->id);
  const std::vector<OtherRegion> others = other_regions(map, *region);
  // Is the space at n (a non-free cell beside the free cell c) known some other way? A wall
  // explains it when it lies across the way from c out through n (up to wall_distance past n's
  // far edge) or runs through n: a wall beside the way, as a door's jamb is beside its
  // opening, does not, so that an opening is a frontier over its whole width.
  const auto explained = [&](const Vector2d& c, const Vector2d& n) {
    const Vector2d far = c + (n - c).normalized() * (res + options.wall_distance);
    for (const auto& [a, b] : walls)
      if (geometry::segments_cross(c, far, a, b) || geometry::point_segment_distance(n, a, b) < 0.5 * res) return true;
    if (distance_to(openings, n) < options.gateway_distance) return true;
    for (const auto& o : others)
      if (o.region->freespace.is_free(o.other_from_this * n)) return true;
    return false;
  };

  // Frontier cells and, per cell, the sum of directions toward its unexplained neighbours.
  std::vector<int8_t> frontier(static_cast<size_t>(w) * h, 0);
  std::vector<Vector2d> outward(frontier.size(), Vector2d::Zero());
  static constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int cy = 0; cy < h; ++cy)
    for (int cx = 0; cx < w; ++cx) {
      if (!fs.free(cx, cy)) continue;
      bool edge = false;
      Vector2d dir = Vector2d::Zero();
      const Vector2d c = centre(cx, cy);
      for (int k = 0; k < 4; ++k) {
        const int nx = cx + kDx[k], ny = cy + kDy[k];
        if (fs.free(nx, ny)) continue;
        edge = true;
        const Vector2d n = centre(nx, ny);
        if (!explained(c, n)) dir += (n - c).normalized();
      }
      if (!edge) continue;
      ++out.edge_cells;
      if (dir.squaredNorm() == 0) continue;
      ++out.frontier_cells;
      const size_t i = static_cast<size_t>(cy) * w + cx;
      frontier[i] = 1;
      outward[i] = dir;
    }

  // 8-connected groups.
  std::vector<int8_t> seen(frontier.size(), 0);
  for (int cy = 0; cy < h; ++cy)
    for (int cx = 0; cx < w; ++cx) {
      const size_t i0 = static_cast<size_t>(cy) * w + cx;
      if (!frontier[i0] || seen[i0]) continue;
      Frontier f;
      f.region_id = region->id;
      Vector2d dir = Vector2d::Zero();
      std::vector<std::pair<int, int>> todo{{cx, cy}};
      seen[i0] = 1;
      while (!todo.empty()) {
        const auto [x, y] = todo.back();
        todo.pop_back();
        const size_t i = static_cast<size_t>(y) * w + x;
        f.cells.push_back(centre(x, y));
        dir += outward[i];
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const size_t j = static_cast<size_t>(ny) * w + nx;
            if (frontier[j] && !seen[j]) {
              seen[j] = 1;
              todo.emplace_back(nx, ny);
            }
          }
      }
      Vector2d lo = f.cells.front(), hi = f.cells.front();
      for (const auto& p : f.cells) {
        f.centroid += p;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      f.centroid /= static_cast<double>(f.cells.size());
      // One cell is a cell wide: extent plus the cell itself.
      f.width = (hi - lo).norm() + res;
      if (f.width < options.min_width) continue;
      f.goal = *std::min_element(f.cells.begin(), f.cells.end(), [&](const Vector2d& a, const Vector2d& b) {
        return (a - f.centroid).squaredNorm() < (b - f.centroid).squaredNorm();
      });
      f.outward = dir.norm() > 1e-9 ? Vector2d(dir.normalized()) : Vector2d(1, 0);
      out.frontiers.push_back(std::move(f));
    }
  std::sort(out.frontiers.begin(), out.frontiers.end(),
            [](const Frontier& a, const Frontier& b) { return a.width > b.width; });
  return out;
}

}  // namespace rgnav::explorer
