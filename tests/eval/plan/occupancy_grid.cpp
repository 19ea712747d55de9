#include "occupancy_grid.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::plan_eval {

using Eigen::Vector2d;
using geometry::Pose2;

OccupancyGrid::OccupancyGrid(double res, const Vector2d& org, int w, int h, uint8_t fill)
    : resolution(res), origin(org), width(w), height(h), cells(static_cast<size_t>(w) * static_cast<size_t>(h), fill)
{
}

Cell OccupancyGrid::cell_of(const Vector2d& p) const
{
  return Cell(static_cast<int>(std::floor((p.x() - origin.x()) / resolution)),
              static_cast<int>(std::floor((p.y() - origin.y()) / resolution)));
}

Vector2d OccupancyGrid::center_of(const Cell& c) const
{
  return origin + resolution * Vector2d(c.x() + 0.5, c.y() + 0.5);
}

void OccupancyGrid::draw_occupied(const Vector2d& a, const Vector2d& b)
{
  Cell p = cell_of(a);
  const Cell q = cell_of(b);
  const int dx = std::abs(q.x() - p.x()), dy = -std::abs(q.y() - p.y());
  const int sx = p.x() < q.x() ? 1 : -1, sy = p.y() < q.y() ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    set(p, kOccupied);
    if (p == q) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      p.x() += sx;
    }
    if (e2 <= dx) {
      err += dx;
      p.y() += sy;
    }
  }
}

void OccupancyGrid::fill_free(const std::vector<Vector2d>& poly)
{
  if (poly.size() < 3 || cells.empty()) return;
  // As rgnav's region grid carves a gateway: OpenCV's convex fill, the cells under the outline
  // included.
  cv::Mat view(height, width, CV_8UC1, cells.data());
  std::vector<cv::Point> pts;
  for (const auto& p : poly) {
    const Cell c = cell_of(p);
    pts.emplace_back(c.x(), c.y());
  }
  cv::fillConvexPoly(view, pts, cv::Scalar(kFree), cv::LINE_8);
}

OccupancyGrid compose_occupancy(const rgmap::RgMap& map, double resolution, double passage_depth,
                                const std::set<int64_t>* only)
{
  struct Placed
  {
    const rgmap::Region* region;
    Pose2 map_from_region;
  };
  std::vector<Placed> placed;
  for (const auto& [id, r] : map.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;
    if (only && !only->count(id)) continue;
    placed.push_back({&r, r.map_from_region});
  }
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  const auto grow = [&](const Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const auto& p : placed) {
    const auto& fs = p.region->freespace;
    const Pose2 map_from_grid = p.map_from_region * fs.region_from_grid();
    const double gw = fs.width() * fs.resolution(), gh = fs.height() * fs.resolution();
    for (const Vector2d& c : {Vector2d(0, 0), Vector2d(gw, 0), Vector2d(0, gh), Vector2d(gw, gh)}) grow(map_from_grid * c);
    for (const auto& s : p.region->segments) {
      grow(p.map_from_region * s.a);
      grow(p.map_from_region * s.b);
    }
  }
  if (lo.x() > hi.x()) return OccupancyGrid(resolution, Vector2d::Zero(), 1, 1);
  const double margin = 0.5;   // [m] unknown all round
  const Vector2d origin = lo - Vector2d::Constant(margin);
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin) / resolution)) + 1;
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin) / resolution)) + 1;
  OccupancyGrid g(resolution, origin, w, h);
  // Inverse mapping: every cell asks each region's bitmap about its centre, so rotated regions
  // leave no holes.
  for (const auto& p : placed) {
    const auto& fs = p.region->freespace;
    if (fs.width() == 0 || fs.height() == 0) continue;
    const Pose2 map_from_grid = p.map_from_region * fs.region_from_grid();
    const double gw = fs.width() * fs.resolution(), gh = fs.height() * fs.resolution();
    Vector2d a = Vector2d::Constant(std::numeric_limits<double>::max()), b = -a;
    for (const Vector2d& c : {Vector2d(0, 0), Vector2d(gw, 0), Vector2d(0, gh), Vector2d(gw, gh)}) {
      a = a.cwiseMin(map_from_grid * c);
      b = b.cwiseMax(map_from_grid * c);
    }
    const Pose2 region_from_map = p.map_from_region.inverse();
    const Cell ca = g.cell_of(a), cb = g.cell_of(b);
    for (int y = std::max(0, ca.y()); y <= std::min(h - 1, cb.y()); ++y)
      for (int x = std::max(0, ca.x()); x <= std::min(w - 1, cb.x()); ++x)
        if (fs.is_free(region_from_map * g.center_of(Cell(x, y)))) g.cells[g.index(Cell(x, y))] = OccupancyGrid::kFree;
  }
  if (passage_depth > 0) {
    for (const auto& [id, gw] : map.gateways()) {
      if (gw.neutralized) continue;
      if (only && gw.region_b != 0 && !only->count(map.resolve(gw.region_b))) continue;
      const auto it = std::find_if(placed.begin(), placed.end(), [&](const Placed& p) { return p.region->id == map.resolve(gw.region_a); });
      if (it == placed.end()) continue;
      std::vector<Vector2d> pts;
      for (const auto& q : gw.gateway_points) pts.push_back(it->map_from_region * q);
      if (pts.size() == 4) {
        g.fill_free(pts);
        continue;
      }
      for (const auto& [a, b] : rgmap::gateway_edges(pts)) {
        const Vector2d d = b - a;
        if (d.norm() < 1e-6) continue;
        const Vector2d n = Vector2d(-d.y(), d.x()).normalized() * passage_depth;
        g.fill_free({a + n, b + n, b - n, a - n});
      }
    }
  }
  // Seams: where two regions' bitmaps (0.15 m cells, each in its own frame) or a carved opening
  // meet, a row of this grid's cells may fall between them. An unknown cell between two free
  // ones (left and right, or below and above) is free.
  std::vector<uint8_t> seams;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const auto at = [&](int cx, int cy) { return g.cells[g.index(Cell(cx, cy))]; };
      if (at(x, y) == OccupancyGrid::kUnknown &&
          ((at(x - 1, y) == OccupancyGrid::kFree && at(x + 1, y) == OccupancyGrid::kFree) ||
           (at(x, y - 1) == OccupancyGrid::kFree && at(x, y + 1) == OccupancyGrid::kFree)))
        seams.push_back(1);
      else
        seams.push_back(0);
    }
  size_t k = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x)
      if (seams[k++]) g.cells[g.index(Cell(x, y))] = OccupancyGrid::kFree;
  for (const auto& p : placed)
    for (const auto& s : p.region->segments) g.draw_occupied(p.map_from_region * s.a, p.map_from_region * s.b);
  return g;
}

ConfigSpace::ConfigSpace(OccupancyGrid grid, double robot_radius) : grid_(std::move(grid)), radius_(robot_radius)
{
  cv::Mat free(grid_.height, grid_.width, CV_8U);
  for (int y = 0; y < grid_.height; ++y)
    for (int x = 0; x < grid_.width; ++x)
      free.at<uint8_t>(y, x) = grid_.cells[grid_.index(Cell(x, y))] == OccupancyGrid::kFree ? 255 : 0;
  // The grid's outer cells are never free (a margin of unknown), so the distance to the border
  // never matters.
  cv::Mat dist;
  cv::distanceTransform(free, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  clearance_.resize(grid_.cells.size());
  for (int y = 0; y < grid_.height; ++y)
    for (int x = 0; x < grid_.width; ++x)
      clearance_[grid_.index(Cell(x, y))] = dist.at<float>(y, x) * static_cast<float>(grid_.resolution);
}

bool ConfigSpace::line_free(const Vector2d& a, const Vector2d& b) const
{
  bool ok = true;
  for_cells_along(grid_, a, b, [&](const Cell& c, bool) { return ok = free(c); });
  return ok;
}

std::optional<Cell> ConfigSpace::nearest_free(const Cell& c, double max_distance) const
{
  if (free(c)) return c;
  const int r = static_cast<int>(std::ceil(max_distance / grid_.resolution));
  std::optional<Cell> best;
  int best_d2 = r * r + 1;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      const int d2 = dx * dx + dy * dy;
      if (d2 >= best_d2) continue;
      const Cell n(c.x() + dx, c.y() + dy);
      if (free(n)) {
        best = n;
        best_d2 = d2;
      }
    }
  return best;
}

}  // namespace rgnav::plan_eval
