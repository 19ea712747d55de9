// What the explorer benchmark measures in the true world, on one raster of it (the ground
// truth's room grid, ground_truth.h): the area the robot could get to see and how much of it it
// saw.
//   - The reachable free area from a start: cells where the robot's centre may stand (clearance to
//     anything the body could hit, doors as at time 0, more than radius + margin) joined to the
//     start's cell 8-connected, widened by the robot radius (what its body can sweep; the floor
//     under a table top is not in it).
//   - The area seen: cells a laser beam of the robot passed through or ended in (true laser pose,
//     measured range, no return taken to max_range), counted where they are reachable free area.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"
#include "sim/world.h"

namespace rgnav::explore_eval {

// A raster of the world frame: cell (cx, cy) covers origin + resolution * [cx, cx+1) x [cy, cy+1).
struct Raster
{
  int width = 0, height = 0;
  double resolution = 0.05;        // [m]
  Eigen::Vector2d origin{0, 0};    // [m] world frame, lower-left corner of cell (0, 0)

  int64_t size() const { return static_cast<int64_t>(width) * height; }
  bool in_bounds(int cx, int cy) const { return cx >= 0 && cy >= 0 && cx < width && cy < height; }
  int64_t index(int cx, int cy) const { return static_cast<int64_t>(cy) * width + cx; }
  // Index of the cell holding p, -1 outside.
  int64_t index_of(const Eigen::Vector2d& p) const;
  Eigen::Vector2d center(int64_t index) const;
};

// Clearance of every cell centre to anything the robot's body could hit in `world` (walls,
// furniture, table tops, doors closed at time 0; people are left out), searched up to `search` [m]
// (farther: search). Cost: one Scene::clearance per cell.
std::vector<float> world_clearance(const sim::World& world, const Raster& raster, double robot_height,
                                   double ground_clearance, double search);

struct ReachableArea
{
  std::vector<uint8_t> stand;   // per cell: the robot's centre may be here and it is joined to the start
  std::vector<uint8_t> free;    // per cell: swept by the body from some `stand` cell
  int64_t stand_cells = 0, free_cells = 0;
  double free_m2 = 0;
};

// From the cell of `start`, or the nearest standable cell within 0.5 m of it (nullopt when there
// is none). `clearance` is per raster cell.
std::optional<ReachableArea> reachable_area(const Raster& raster, const std::vector<float>& clearance,
                                            const Eigen::Vector2d& start, double radius, double margin);

// A random cell centre of `area.stand` whose clearance is at least `min_clearance`.
std::optional<Eigen::Vector2d> random_standable(const Raster& raster, const ReachableArea& area,
                                                const std::vector<float>& clearance, double min_clearance,
                                                std::mt19937_64& rng);

// Cells a beam from `from` to `to` (world frame) passes through, `to`'s cell included, in order
// (Amanatides-Woo traversal, clipped to the raster). Calls f(index) for each.
template <typename F>
void trace_ray(const Raster& raster, const Eigen::Vector2d& from, const Eigen::Vector2d& to, F&& f);

class SeenArea
{
 public:
  // `counted`: per cell, whether it is part of the area measured (reachable free area).
  SeenArea(const Raster& raster, std::vector<uint8_t> counted);

  // One scan at the true laser pose; beams longer than max_range (and no returns) end there.
  void add_scan(const geometry::Pose2& world_from_laser, const sensors::LaserScan& scan, double max_range);
  int64_t counted_cells() const { return counted_cells_; }
  int64_t seen_counted_cells() const { return seen_counted_; }
  double ratio() const { return counted_cells_ > 0 ? static_cast<double>(seen_counted_) / counted_cells_ : 0.0; }
  const std::vector<uint8_t>& seen() const { return seen_; }

 private:
  Raster raster_;
  std::vector<uint8_t> counted_;
  std::vector<uint8_t> seen_;
  int64_t counted_cells_ = 0, seen_counted_ = 0;
};

// ---- template implementation ----

template <typename F>
void trace_ray(const Raster& raster, const Eigen::Vector2d& from, const Eigen::Vector2d& to, F&& f)
{
  const Eigen::Vector2d a = (from - raster.origin) / raster.resolution;
  const Eigen::Vector2d b = (to - raster.origin) / raster.resolution;
  int cx = static_cast<int>(std::floor(a.x())), cy = static_cast<int>(std::floor(a.y()));
  const int ex = static_cast<int>(std::floor(b.x())), ey = static_cast<int>(std::floor(b.y()));
  const Eigen::Vector2d d = b - a;
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double dtx = d.x() != 0 ? std::abs(1.0 / d.x()) : inf, dty = d.y() != 0 ? std::abs(1.0 / d.y()) : inf;
  double tx = d.x() != 0 ? (d.x() > 0 ? (cx + 1 - a.x()) : (a.x() - cx)) * dtx : inf;
  double ty = d.y() != 0 ? (d.y() > 0 ? (cy + 1 - a.y()) : (a.y() - cy)) * dty : inf;
  const int steps = std::abs(ex - cx) + std::abs(ey - cy);
  for (int k = 0; k <= steps; ++k) {
    if (raster.in_bounds(cx, cy)) f(raster.index(cx, cy));
    if (tx < ty) {
      tx += dtx;
      cx += sx;
    } else {
      ty += dty;
      cy += sy;
    }
  }
}

}  // namespace rgnav::explore_eval
