// A region rendered for path planning (diss. 5.4): its 2D line map drawn into an occupancy grid
// with Bresenham's algorithm, everything its freespace bitmap does not call free counted as
// occupied (unknown is not free), and the distance of every cell to the nearest occupied one.
// A cell nearer a wall than the robot radius, or nearer unknown space than the radius less
// unknown_overlap (freshly mapped space is ragged at its edges), is blocked; nearer than
// radius + margin + comfort width to either it costs more per metre, in a few quantised levels
// (level 0: no extra cost; the body over unknown space: the dearest), so that the path
// keeps away from walls where the passage allows and wide passages are preferred to narrow ones.
// The grid is axis-aligned with the region frame. It reaches neighbour_margin beyond the region
// and sees the neighbouring regions there (through the gateways' transforms): their free cells
// are free where the region itself knows nothing, so that a gateway's opening is not a wall of
// unknown and a small region (a crossing's square) has room. The gateways' own openings are free
// too (the RG kernel trims a region's freespace at narrow passages, doors included): a door's
// line widened to passage_depth each side, a crossing's outline filled. A line wholly inside a
// door's or passage's opening, clear of its jambs, is left out (something that stood in a way the
// robot has gone through; collision avoidance sees whether it still does); a shut door's leaf,
// reaching the jambs, stays.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <vector>

#include "planner/planner_options.h"

namespace cv { class Mat; }
#include "rgmap/rg_map.h"

namespace rgnav::planner {

using Cell = Eigen::Vector2i;

// A region beside this one, and where it lies: its frame in this region's.
struct NeighbourRegion
{
  const rgmap::Region* region = nullptr;
  geometry::Pose2 this_from_other;
};

class RegionGrid
{
 public:
  // gateways: each gateway of the region as its points in the region frame (rgmap::gateway_edges).
  // blocked: places (region frame) where collision avoidance could not pass, obstacles of
  // options.blocked_radius as solid as the map's lines.
  RegionGrid(const rgmap::Region& region, const GridOptions& options, const std::vector<NeighbourRegion>& neighbours = {},
             const std::vector<std::vector<Eigen::Vector2d>>& gateways = {},
             const std::vector<Eigen::Vector2d>& blocked = {});

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  bool in_bounds(const Cell& c) const { return c.x() >= 0 && c.y() >= 0 && c.x() < width_ && c.y() < height_; }
  // Traversable by the robot's centre (clearance >= robot radius).
  bool free(const Cell& c) const { return in_bounds(c) && level_[index(c)] != kBlocked; }
  // [m] distance from the cell centre to the nearest occupied cell.
  float clearance(const Cell& c) const { return clearance_[index(c)]; }
  // Cost level of a free cell (0 = open space); kBlocked when blocked.
  uint8_t level(const Cell& c) const { return level_[index(c)]; }
  // Cost per metre in a cell of this level (1 for level 0).
  double level_cost(uint8_t level) const { return level_cost_[level]; }
  double max_level_cost() const { return level_cost_.back(); }
  // Cost of the straight line a->b: its length weighted by the level cost of the cells it
  // crosses (sampled every half cell); nullopt when a cell on it is blocked.
  std::optional<double> line_cost(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // The smallest clearance along a->b [m].
  double line_clearance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  Cell cell_of(const Eigen::Vector2d& region_point) const;
  Eigen::Vector2d center_of(const Cell& c) const;
  // The free cell nearest to `c` within `reach` metres (options.adapt_distance if < 0) that is
  // connected to the region's own freespace, preferring higher clearance among equally near
  // ones (start and goal adaption); nullopt if none.
  std::optional<Cell> nearest_free(const Cell& c, double reach = -1) const;
  // The connected piece of free cells `c` belongs to (8-connected; 0: blocked or outside). Ragged
  // freespace leaves scraps beside the region's main space, a place among furniture one too.
  int32_t component(const Cell& c) const { return in_bounds(c) ? component_[index(c)] : 0; }
  // The largest piece of the region's own free cells: where the region's ways on are.
  int32_t main_component() const { return main_component_; }
  // The piece is the main one, or a part of the main space only blocked places cut from it.
  bool in_main_space(int32_t piece) const;
  // [m] distance from the cell centre to the nearest line of the region's map (or the grid's edge).
  float wall_clearance(const Cell& c) const { return in_bounds(c) ? wall_clearance_[index(c)] : 0.f; }
  // The robot's body stands at `from` whatever the grid calls the cells around it (unknown space
  // behind a laser that sees only ahead, scraps of ragged freespace): the nearest free cell of
  // `piece` within `reach` [m] that the robot gets to straight from where it stands, the line
  // coming no nearer a line of the map than the robot radius (or than it stands now, if nearer).
  // nullopt if none.
  std::optional<Cell> nearest_reachable_in(const Eigen::Vector2d& from, int32_t piece, double reach) const;
  // The straight line from the robot's place `from` to `to` comes no nearer a line of the map
  // than the robot radius, or than the robot stands now if nearer (the rule of nearest_reachable_in).
  bool clear_of_lines(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;

  static constexpr uint8_t kBlocked = 255;

 private:
  size_t index(const Cell& c) const { return static_cast<size_t>(c.y()) * width_ + c.x(); }
  void carve_gateway(cv::Mat& free_mask, const std::vector<Eigen::Vector2d>& points) const;
  // The segment a-b lies wholly inside a door's or narrow passage's opening, clear of its ends.
  bool in_an_opening(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const std::vector<std::vector<Eigen::Vector2d>>& gateways) const;

  GridOptions options_;
  double resolution_ = 0.05;
  Eigen::Vector2d origin_{0, 0};  // region frame, corner of cell (0,0)
  int width_ = 0, height_ = 0;
  std::vector<float> clearance_;
  std::vector<uint8_t> level_;
  std::vector<uint8_t> own_;   // 1: free and connected to the region's own freespace
  std::vector<int32_t> component_;   // connected piece of free cells (0: blocked)
  int32_t main_component_ = 0;
  std::vector<uint8_t> main_pieces_;   // per piece: in_main_space
  std::vector<float> wall_clearance_;   // [m] to the nearest line of the map
  std::vector<double> level_cost_;
};

}  // namespace rgnav::planner
