#include "world_coverage.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "sim/scene.h"

namespace rgnav::explore_eval {

int64_t Raster::index_of(const Eigen::Vector2d& p) const
{
  const int cx = static_cast<int>(std::floor((p.x() - origin.x()) / resolution));
  const int cy = static_cast<int>(std::floor((p.y() - origin.y()) / resolution));
  return in_bounds(cx, cy) ? index(cx, cy) : -1;
}

Eigen::Vector2d Raster::center(int64_t i) const
{
  return origin + resolution * Eigen::Vector2d(static_cast<double>(i % width) + 0.5, static_cast<double>(i / width) + 0.5);
}

std::vector<float> world_clearance(const sim::World& world, const Raster& raster, double robot_height,
                                   double ground_clearance, double search)
{
  const sim::Scene scene(world);
  std::vector<uint8_t> doors(world.doors.size());
  for (size_t i = 0; i < world.doors.size(); ++i) doors[i] = world.doors[i].open_at(0.0) ? 1 : 0;
  const sim::HeightBand band{ground_clearance, robot_height};
  std::vector<float> c(static_cast<size_t>(raster.size()));
  for (int64_t i = 0; i < raster.size(); ++i)
    c[static_cast<size_t>(i)] = static_cast<float>(std::min(search, scene.clearance(raster.center(i), search, band, doors).distance));
  return c;
}

std::optional<ReachableArea> reachable_area(const Raster& raster, const std::vector<float>& clearance,
                                            const Eigen::Vector2d& start, double radius, double margin)
{
  const double need = radius + margin;
  const auto standable = [&](int64_t i) { return clearance[static_cast<size_t>(i)] > need; };
  // The start's cell, or the nearest standable one within 0.5 m.
  int64_t seed = -1;
  double best = 0.5;
  const int reach = static_cast<int>(std::ceil(0.5 / raster.resolution));
  const int scx = static_cast<int>(std::floor((start.x() - raster.origin.x()) / raster.resolution));
  const int scy = static_cast<int>(std::floor((start.y() - raster.origin.y()) / raster.resolution));
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      if (!raster.in_bounds(scx + dx, scy + dy)) continue;
      const int64_t i = raster.index(scx + dx, scy + dy);
      const double d = (raster.center(i) - start).norm();
      if (standable(i) && d <= best) {
        best = d;
        seed = i;
      }
    }
  if (seed < 0) return std::nullopt;
  ReachableArea a;
  a.stand.assign(static_cast<size_t>(raster.size()), 0);
  a.free.assign(static_cast<size_t>(raster.size()), 0);
  std::vector<int64_t> open{seed};
  a.stand[static_cast<size_t>(seed)] = 1;
  while (!open.empty()) {
    const int64_t i = open.back();
    open.pop_back();
    ++a.stand_cells;
    const int cx = static_cast<int>(i % raster.width), cy = static_cast<int>(i / raster.width);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !raster.in_bounds(cx + dx, cy + dy)) continue;
        const int64_t j = raster.index(cx + dx, cy + dy);
        if (a.stand[static_cast<size_t>(j)] || !standable(j)) continue;
        a.stand[static_cast<size_t>(j)] = 1;
        open.push_back(j);
      }
  }
  // Widened by the radius: every cell whose centre lies within `radius` of a stand cell's centre.
  const int r = static_cast<int>(std::floor(radius / raster.resolution));
  std::vector<std::pair<int, int>> disc;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      if (std::hypot(dx, dy) * raster.resolution <= radius) disc.emplace_back(dx, dy);
  for (int64_t i = 0; i < raster.size(); ++i) {
    if (!a.stand[static_cast<size_t>(i)]) continue;
    const int cx = static_cast<int>(i % raster.width), cy = static_cast<int>(i / raster.width);
    // Inner cells: their whole disc is made of stand cells' discs already covered by neighbours;
    // only cells at the edge of the stand area widen it.
    bool edge = false;
    for (int k = 0; k < 4 && !edge; ++k) {
      const int nx = cx + (k == 0) - (k == 1), ny = cy + (k == 2) - (k == 3);
      edge = !raster.in_bounds(nx, ny) || !a.stand[static_cast<size_t>(raster.index(nx, ny))];
    }
    if (!edge) {
      a.free[static_cast<size_t>(i)] = 1;
      continue;
    }
    for (const auto& [dx, dy] : disc)
      if (raster.in_bounds(cx + dx, cy + dy)) a.free[static_cast<size_t>(raster.index(cx + dx, cy + dy))] = 1;
  }
  a.free_cells = std::count(a.free.begin(), a.free.end(), uint8_t{1});
  a.free_m2 = static_cast<double>(a.free_cells) * raster.resolution * raster.resolution;
  return a;
}

std::optional<Eigen::Vector2d> random_standable(const Raster& raster, const ReachableArea& area,
                                                const std::vector<float>& clearance, double min_clearance,
                                                std::mt19937_64& rng)
{
  std::vector<int64_t> cells;
  for (int64_t i = 0; i < raster.size(); ++i)
    if (area.stand[static_cast<size_t>(i)] && clearance[static_cast<size_t>(i)] >= min_clearance) cells.push_back(i);
  if (cells.empty()) return std::nullopt;
  return raster.center(cells[std::uniform_int_distribution<size_t>(0, cells.size() - 1)(rng)]);
}

SeenArea::SeenArea(const Raster& raster, std::vector<uint8_t> counted)
    : raster_(raster), counted_(std::move(counted)), seen_(static_cast<size_t>(raster.size()), 0)
{
  counted_cells_ = std::count(counted_.begin(), counted_.end(), uint8_t{1});
}

void SeenArea::add_scan(const geometry::Pose2& world_from_laser, const sensors::LaserScan& scan, double max_range)
{
  const Eigen::Vector2d from = world_from_laser.translation();
  for (size_t b = 0; b < scan.size(); ++b) {
    if (scan.invalid(b)) continue;
    const double range = scan.hit(b) ? std::min<double>(scan.ranges[b], max_range) : max_range;
    const Eigen::Vector2d to = world_from_laser * (range * scan.direction(b));
    trace_ray(raster_, from, to, [&](int64_t i) {
      auto& s = seen_[static_cast<size_t>(i)];
      if (s) return;
      s = 1;
      seen_counted_ += counted_[static_cast<size_t>(i)];
    });
  }
}

}  // namespace rgnav::explore_eval
