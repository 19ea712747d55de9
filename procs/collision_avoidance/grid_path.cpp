#include "collision_avoidance/grid_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "collision_avoidance/local_grid.h"

namespace rgnav::collision_avoidance {

std::optional<std::vector<Eigen::Vector2d>> grid_path(const LocalMap& map, const Eigen::Vector2d& from,
                                                      const Eigen::Vector2d& to, double clearance,
                                                      const GridPathOptions& o)
{
  const Eigen::Vector2d lo = from.cwiseMin(to).array() - o.margin;
  const Eigen::Vector2d hi = from.cwiseMax(to).array() + o.margin;
  if ((hi - lo).maxCoeff() > o.max_extent) return std::nullopt;
  const LocalGrid grid(map, lo, hi, o.cell);
  const int w = grid.width(), h = grid.height();

  // Space some kept scan saw free is passable. So is its shadow (within the scanner's field
  // of view, behind what it hit), at a higher cost: a target behind a box lies there. Outside
  // every field of view (behind the robot) nothing is known, and "unknown = free" there would
  // send the robot around the building: not passable, except right around the robot.
  const Eigen::Vector2i s = grid.cell_of(from), g = grid.cell_of(to);
  const double start_clr = grid.clearance(s.x(), s.y());
  // The grid's clearance is on the safe side by up to a cell diagonal: between walls with only
  // centimetres to spare (a narrow hallway, a door) it would close the way. There the exact
  // clearance of the cell's centre decides.
  auto clear = [&](int x, int y) {
    const double c = grid.clearance(x, y);
    return c >= clearance || (c >= clearance - 1.5 * o.cell && map.clearance(grid.centre(x, y), clearance) >= clearance);
  };
  if (!clear(g.x(), g.y()) || !grid.in_view(g.x(), g.y())) return std::nullopt;
  auto passable = [&](int x, int y) {
    const double from_start = (grid.centre(x, y) - from).norm();
    if (!grid.in_view(x, y) && from_start > 0.5) return false;
    if (clear(x, y)) return true;
    // Leaving a tight spot: near the start, cells no tighter than the start.
    return from_start <= 0.3 && grid.clearance(x, y) >= start_clr;
  };

  const int n = w * h;
  std::vector<double> cost(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  std::vector<int> parent(static_cast<size_t>(n), -1);
  std::vector<uint8_t> closed(static_cast<size_t>(n), 0);
  using Item = std::pair<double, int>;  // f, index
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  auto heuristic = [&](int x, int y) { return std::hypot(x - g.x(), y - g.y()) * o.cell; };
  cost[static_cast<size_t>(grid.index(s.x(), s.y()))] = 0.0;
  open.emplace(heuristic(s.x(), s.y()), grid.index(s.x(), s.y()));
  bool found = false;
  while (!open.empty()) {
    const int cur = open.top().second;
    open.pop();
    if (closed[static_cast<size_t>(cur)]) continue;
    closed[static_cast<size_t>(cur)] = 1;
    const int cx = cur % w, cy = cur / w;
    if (cx == g.x() && cy == g.y()) {
      found = true;
      break;
    }
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int nx = cx + dx, ny = cy + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const int ni = grid.index(nx, ny);
        if (closed[static_cast<size_t>(ni)] || !passable(nx, ny)) continue;
        const double tight = std::clamp((clearance + o.comfort - grid.clearance(nx, ny)) / o.comfort, 0.0, 1.0);
        const double shadow = grid.seen(nx, ny) ? 1.0 : o.shadow_cost;
        const double step = (dx != 0 && dy != 0 ? M_SQRT2 : 1.0) * o.cell * (1.0 + o.comfort_weight * tight) * shadow;
        const double c = cost[static_cast<size_t>(cur)] + step;
        if (c < cost[static_cast<size_t>(ni)]) {
          cost[static_cast<size_t>(ni)] = c;
          parent[static_cast<size_t>(ni)] = cur;
          open.emplace(c + heuristic(nx, ny), ni);
        }
      }
  }
  if (!found) return std::nullopt;

  std::vector<Eigen::Vector2d> cells;
  for (int i = grid.index(g.x(), g.y()); i >= 0; i = parent[static_cast<size_t>(i)]) cells.push_back(grid.centre(i % w, i / w));
  std::reverse(cells.begin(), cells.end());
  cells.front() = from;
  cells.back() = to;
  return line_of_sight_corners(map, cells, clearance);
}

}  // namespace rgnav::collision_avoidance
