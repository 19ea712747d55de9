// Planning inside one region (diss. 5.4): the framed quadtree search on the region's grid, start
// and goal adapted onto free cells, then smoothing: a waypoint is dropped when the straight line
// past it is free and no dearer than the way through it (so the path shortens but does not
// creep toward walls). Built once per region description and reused for every query.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "planner/framed_quadtree.h"
#include "planner/region_grid.h"

namespace rgnav::planner {

struct RegionPath
{
  std::vector<Eigen::Vector2d> points;  // region frame, from start to goal (adapted ends included)
  double length = 0;                    // [m]
  double cost = 0;                      // [m] length weighted by the wall cost
  double min_clearance = 0;             // [m] smallest distance to an occupied cell along the path
  int expanded = 0;                     // search effort
};

class RegionPlanner
{
 public:
  RegionPlanner(const rgmap::Region& region, const GridOptions& options, const std::vector<NeighbourRegion>& neighbours = {},
                const std::vector<std::vector<Eigen::Vector2d>>& gateways = {},
                const std::vector<Eigen::Vector2d>& blocked = {});

  // A path from `from` to `to`; each end may be moved onto a free cell up to its reach [m]
  // (< 0: GridOptions::adapt_distance). With to_clear_of_walls the straight piece from the
  // free cell to a moved `to` must cross no line of the region's map (a goal in unknown space
  // past the freespace, reached through an opening, not through a wall). With from_is_robot the
  // robot stands at `from`: when the nearest free cell there is a scrap of free space apart from
  // the one `to` is in (ragged freespace, unknown cells round a robot whose laser sees only
  // ahead), `from` joins `to`'s piece at its nearest cell within reach that the robot gets to
  // straight, clear of the map's lines. nullopt with *why set when there is none.
  std::optional<RegionPath> plan(const Eigen::Vector2d& from, const Eigen::Vector2d& to, std::string* why = nullptr,
                                 double from_reach = -1, double to_reach = -1, bool to_clear_of_walls = false,
                                 bool from_is_robot = false) const;
  const RegionGrid& grid() const { return grid_; }
  const FramedQuadtree& tree() const { return tree_; }
  // Whether the robot can stand at p (free, or adaptable onto a free cell within reach).
  bool standable(const Eigen::Vector2d& p, double reach = -1) const;
  // The robot at p is cut off from the region's main free space: no cell of it within reach
  // (< 0: adapt_distance) that it gets to straight, clear of the map's lines. Standing there,
  // nothing changes that.
  bool cut_off(const Eigen::Vector2d& p, double reach = -1) const;
  // The straight line a->b crosses a line of the region's map.
  bool crosses_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

 private:
  std::vector<Eigen::Vector2d> smooth(const std::vector<Eigen::Vector2d>& points) const;

  GridOptions grid_options_;
  RegionGrid grid_;
  FramedQuadtree tree_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls_;   // the region's line map
};

}  // namespace rgnav::planner
