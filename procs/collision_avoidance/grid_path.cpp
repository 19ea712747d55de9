#include "collision_avoidance/grid_path.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace rgnav::collision_avoidance {

namespace {

// Straight leg a -> b keeps `clearance` from the map's points (sampled every 5 cm); where the
// start is already closer than that, the leg may not get closer than the start is.
bool leg_free(const LocalMap& map, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double clearance,
              double start_clearance)
{
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / 0.05)));
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
    const double need = std::min(clearance, start_clearance);
    if (map.clearance(p, clearance) < need - 1e-9) return false;
  }
  return true;
}

}  // namespace

std::optional<std::vector<Eigen::Vector2d>> grid_path(const LocalMap& map, const Eigen::Vector2d& from,
                                                      const Eigen::Vector2d& to, double clearance,
                                                      const GridPathOptions& o)
{
  const Eigen::Vector2d lo = from.cwiseMin(to).array() - o.margin;
  const Eigen::Vector2d hi = from.cwiseMax(to).array() + o.margin;
  if ((hi - lo).maxCoeff() > o.max_extent) return std::nullopt;
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / o.cell));
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y()) / o.cell));
  auto cell_of = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2i(std::clamp(static_cast<int>(std::floor((p.x() - lo.x()) / o.cell)), 0, w - 1),
                           std::clamp(static_cast<int>(std::floor((p.y() - lo.y()) / o.cell)), 0, h - 1));
  };
  auto centre = [&](int x, int y) { return Eigen::Vector2d(lo.x() + (x + 0.5) * o.cell, lo.y() + (y + 0.5) * o.cell); };

  // Obstacles are the zero pixels of the distance transform's input.
  cv::Mat free_img(h, w, CV_8UC1, cv::Scalar(255));
  for (const auto& p : map.points()) {
    if (p.x() < lo.x() || p.y() < lo.y() || p.x() >= hi.x() || p.y() >= hi.y()) continue;
    const Eigen::Vector2i c = cell_of(p);
    free_img.at<uint8_t>(c.y(), c.x()) = 0;
  }
  cv::Mat dist;
  cv::distanceTransform(free_img, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // Obstacle points sit anywhere in their cell: subtract half a diagonal to stay on the safe side.
  auto clr = [&](int x, int y) { return std::max(0.0, dist.at<float>(y, x) * o.cell - 0.71 * o.cell); };

  // Space some kept scan saw free is passable. So is its shadow (within the scanner's field
  // of view, behind what it hit), at a higher cost: a target behind a box lies there. Outside
  // every field of view (behind the robot) nothing is known, and "unknown = free" there would
  // send the robot around the building: not passable, except right around the robot.
  cv::Mat seen(h, w, CV_8UC1, cv::Scalar(0)), cone(h, w, CV_8UC1, cv::Scalar(0));
  std::vector<const ScanPoints*> views;
  for (const auto& sc : map.views()) views.push_back(&sc);
  for (const auto& sc : map.scans()) views.push_back(&sc);
  for (const ScanPoints* view : views) {
    const ScanPoints& sc = *view;
    if (sc.outline.empty()) continue;
    auto px = [&](const Eigen::Vector2d& base) {
      const Eigen::Vector2d p = sc.odom_from_base * base;
      return cv::Point(static_cast<int>(std::floor((p.x() - lo.x()) / o.cell)),
                       static_cast<int>(std::floor((p.y() - lo.y()) / o.cell)));
    };
    std::vector<cv::Point> vis{px(sc.laser_origin)}, fov{px(sc.laser_origin)};
    const double far = hi.x() - lo.x() + hi.y() - lo.y();
    for (const auto& e : sc.outline) {
      vis.push_back(px(e));
      const Eigen::Vector2d d = e - sc.laser_origin;
      if (d.norm() > 1e-6) fov.push_back(px(sc.laser_origin + d.normalized() * far));
    }
    cv::fillPoly(cone, std::vector<std::vector<cv::Point>>{fov}, cv::Scalar(255));
    cv::fillPoly(seen, std::vector<std::vector<cv::Point>>{vis}, cv::Scalar(255));
  }
  const Eigen::Vector2i s = cell_of(from), g = cell_of(to);
  const double start_clr = clr(s.x(), s.y());
  auto known = [&](int x, int y) { return seen.at<uint8_t>(y, x) || cone.at<uint8_t>(y, x); };
  if (clr(g.x(), g.y()) < clearance || !known(g.x(), g.y())) return std::nullopt;
  auto passable = [&](int x, int y) {
    const double c = clr(x, y);
    const double from_start = (centre(x, y) - from).norm();
    if (!known(x, y) && from_start > 0.5) return false;
    if (c >= clearance) return true;
    // Leaving a tight spot: near the start, cells no tighter than the start.
    return from_start <= 0.3 && c >= start_clr;
  };

  const int n = w * h;
  std::vector<double> cost(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  std::vector<int> parent(static_cast<size_t>(n), -1);
  std::vector<uint8_t> closed(static_cast<size_t>(n), 0);
  using Item = std::pair<double, int>;  // f, index
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  auto idx = [w](int x, int y) { return y * w + x; };
  auto heuristic = [&](int x, int y) { return std::hypot(x - g.x(), y - g.y()) * o.cell; };
  cost[static_cast<size_t>(idx(s.x(), s.y()))] = 0.0;
  open.emplace(heuristic(s.x(), s.y()), idx(s.x(), s.y()));
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
        const int ni = idx(nx, ny);
        if (closed[static_cast<size_t>(ni)] || !passable(nx, ny)) continue;
        const double tight = std::clamp((clearance + o.comfort - clr(nx, ny)) / o.comfort, 0.0, 1.0);
        const double shadow = seen.at<uint8_t>(ny, nx) ? 1.0 : o.shadow_cost;
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
  for (int i = idx(g.x(), g.y()); i >= 0; i = parent[static_cast<size_t>(i)]) cells.push_back(centre(i % w, i / w));
  std::reverse(cells.begin(), cells.end());
  cells.front() = from;
  cells.back() = to;

  // Line of sight: from each corner, the farthest path point reachable in a straight free leg.
  std::vector<Eigen::Vector2d> corners;
  size_t i = 0;
  while (i + 1 < cells.size()) {
    size_t best = i + 1;  // the grid's own step is trusted when nothing longer is free
    const double sc = i == 0 ? map.clearance(from, clearance) : clearance;
    // Growing the leg until it first touches: linear in the path length per corner.
    for (size_t j = i + 2; j < cells.size() && leg_free(map, cells[i], cells[j], clearance, sc); ++j) best = j;
    corners.push_back(cells[best]);
    i = best;
  }
  return corners;
}

}  // namespace rgnav::collision_avoidance
