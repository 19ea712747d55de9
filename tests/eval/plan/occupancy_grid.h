// The whole-building occupancy the planning benchmark measures rgnav's routes against: one grid
// in the map frame composed from every live region of an RG map (a cell is free when a region's
// freespace bitmap calls its centre free; the regions' line segments are drawn over it as
// occupied; everything else is unknown), and its configuration space for a round robot (a cell
// is free for the robot's centre when it is at least the robot radius from every cell that is
// not free). This is the "same occupancy" rgnav plans on, without the region boundaries.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <optional>
#include <vector>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"

namespace rgnav::plan_eval {

using Cell = Eigen::Vector2i;

struct OccupancyGrid
{
  enum : uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };
  double resolution = 0.05;          // [m] cell edge
  Eigen::Vector2d origin{0, 0};      // [m] map frame, lower-left corner of cell (0,0)
  int width = 0, height = 0;
  std::vector<uint8_t> cells;        // row-major, row 0 at the lowest y

  OccupancyGrid() = default;
  OccupancyGrid(double resolution, const Eigen::Vector2d& origin, int width, int height, uint8_t fill = kUnknown);
  bool in_bounds(const Cell& c) const { return c.x() >= 0 && c.y() >= 0 && c.x() < width && c.y() < height; }
  size_t index(const Cell& c) const { return static_cast<size_t>(c.y()) * static_cast<size_t>(width) + static_cast<size_t>(c.x()); }
  uint8_t at(const Cell& c) const { return in_bounds(c) ? cells[index(c)] : static_cast<uint8_t>(kUnknown); }
  void set(const Cell& c, uint8_t v)
  {
    if (in_bounds(c)) cells[index(c)] = v;
  }
  Cell cell_of(const Eigen::Vector2d& p) const;
  Eigen::Vector2d center_of(const Cell& c) const;
  // Marks the cells of the segment a-b (map frame) occupied (Bresenham).
  void draw_occupied(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  // Marks free every cell the convex polygon (map frame) covers or touches.
  void fill_free(const std::vector<Eigen::Vector2d>& convex);
};

// Every cell the straight line a -> b (map frame) passes, in order, b's last (Amanatides & Woo's
// traversal): f(cell, last) returns false to stop there.
template <typename F>
void for_cells_along(const OccupancyGrid& g, const Eigen::Vector2d& a, const Eigen::Vector2d& b, F&& f)
{
  const Eigen::Vector2d pa = (a - g.origin) / g.resolution, pb = (b - g.origin) / g.resolution;
  Cell c(static_cast<int>(std::floor(pa.x())), static_cast<int>(std::floor(pa.y())));
  const Cell end(static_cast<int>(std::floor(pb.x())), static_cast<int>(std::floor(pb.y())));
  const Eigen::Vector2d d = pb - pa;
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double dtx = d.x() != 0 ? std::abs(1.0 / d.x()) : inf, dty = d.y() != 0 ? std::abs(1.0 / d.y()) : inf;
  double tx = d.x() != 0 ? (sx > 0 ? (c.x() + 1 - pa.x()) : (pa.x() - c.x())) * dtx : inf;
  double ty = d.y() != 0 ? (sy > 0 ? (c.y() + 1 - pa.y()) : (pa.y() - c.y())) * dty : inf;
  const int steps = std::abs(end.x() - c.x()) + std::abs(end.y() - c.y());
  for (int k = 0; k <= steps; ++k) {
    if (!f(static_cast<const Cell&>(c), k == steps)) return;
    if (tx < ty) {
      c.x() += sx;
      tx += dtx;
    } else {
      c.y() += sy;
      ty += dty;
    }
  }
}

// Every live region of `map` (or those in `only`, and the gateways between them) placed by its
// map_from_region, at `resolution`, over their extent. With passage_depth > 0 the
// openings of the gateways are free as rgnav's planner takes them (the RG kernel trims a
// region's freespace at narrow passages, doors included): a crossing's outline filled, any
// other gateway's lines widened to passage_depth each side. An unknown cell between two free
// ones (a seam where two regions' bitmaps meet) is free. The line segments are drawn last.
OccupancyGrid compose_occupancy(const rgmap::RgMap& map, double resolution, double passage_depth = 0.0,
                                const std::set<int64_t>* only = nullptr);

// The configuration space of a round robot on an occupancy grid.
class ConfigSpace
{
 public:
  ConfigSpace(OccupancyGrid grid, double robot_radius);

  const OccupancyGrid& grid() const { return grid_; }
  double robot_radius() const { return radius_; }
  // [m] from the cell centre to the centre of the nearest cell that is not free (exact
  // Euclidean); 0 for a cell that is not free itself or lies outside.
  float clearance(const Cell& c) const { return grid_.in_bounds(c) ? clearance_[grid_.index(c)] : 0.0f; }
  // [m] clearance of the cell holding p (map frame).
  double clearance_at(const Eigen::Vector2d& p) const { return clearance(grid_.cell_of(p)); }
  bool free(const Cell& c) const { return clearance(c) >= radius_; }
  // Every cell the straight line a-b (map frame) passes is free.
  bool line_free(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // The free cell nearest to c no farther than max_distance [m] (c itself when free).
  std::optional<Cell> nearest_free(const Cell& c, double max_distance) const;

 private:
  OccupancyGrid grid_;
  double radius_;
  std::vector<float> clearance_;
};

}  // namespace rgnav::plan_eval
