#include "sim/tour_planner.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <set>
#include <sstream>

namespace rgnav::sim {

namespace {

std::vector<uint8_t> doors_at_start(const World& w)
{
  std::vector<uint8_t> open(w.doors.size());
  for (size_t i = 0; i < w.doors.size(); ++i) open[i] = w.doors[i].open_at(0.0) ? 1 : 0;
  return open;
}

class Grid
{
 public:
  Grid(const Scene& scene, double res) : res_(res)
  {
    origin_ = scene.min_corner();
    const Vec2 size = scene.max_corner() - origin_;
    cols_ = static_cast<int>(std::ceil(size.x() / res));
    rows_ = static_cast<int>(std::ceil(size.y() / res));
  }
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  int size() const { return cols_ * rows_; }
  Vec2 center(int i) const { return origin_ + Vec2((i % cols_ + 0.5) * res_, (i / cols_ + 0.5) * res_); }
  int index(const Vec2& p) const
  {
    const int c = static_cast<int>(std::floor((p.x() - origin_.x()) / res_));
    const int r = static_cast<int>(std::floor((p.y() - origin_.y()) / res_));
    if (c < 0 || r < 0 || c >= cols_ || r >= rows_) return -1;
    return r * cols_ + c;
  }

 private:
  Vec2 origin_;
  double res_;
  int cols_ = 0, rows_ = 0;
};

struct Planner
{
  const World& world;
  const RobotOptions& robot;
  const TourOptions& opt;
  Scene scene;
  std::vector<uint8_t> doors;
  Grid grid;
  std::vector<uint8_t> free;   // configuration-space free cells
  std::vector<float> penalty;  // extra cost per metre near obstacles

  Planner(const World& w, const RobotOptions& r, const TourOptions& o)
      : world(w), robot(r), opt(o), scene(w), doors(doors_at_start(w)), grid(scene, o.resolution)
  {
    const HeightBand band{robot.ground_clearance, robot.height};
    const double need = robot.radius + opt.margin;
    free.assign(static_cast<size_t>(grid.size()), 0);
    cv::Mat mask(grid.rows(), grid.cols(), CV_8U, cv::Scalar(0));
    for (int i = 0; i < grid.size(); ++i) {
      const double c = scene.clearance(grid.center(i), need, band, doors).distance;
      if (c > need) {
        free[static_cast<size_t>(i)] = 1;
        mask.at<uint8_t>(i / grid.cols(), i % grid.cols()) = 255;
      }
    }
    cv::Mat dist;
    cv::distanceTransform(mask, dist, cv::DIST_L2, 5);
    penalty.assign(free.size(), 0.f);
    for (int i = 0; i < grid.size(); ++i) {
      const double d = dist.at<float>(i / grid.cols(), i % grid.cols()) * opt.resolution;
      penalty[static_cast<size_t>(i)] = static_cast<float>(4.0 * std::max(0.0, 1.0 - d / opt.comfort_distance));
    }
  }

  // Dijkstra from `from` over free cells (8-connected, no corner cutting).
  void costs_from(int from, std::vector<double>* cost, std::vector<int>* parent) const
  {
    cost->assign(free.size(), std::numeric_limits<double>::infinity());
    parent->assign(free.size(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    (*cost)[static_cast<size_t>(from)] = 0.0;
    queue.push({0.0, from});
    const int cols = grid.cols();
    const int dc[8] = {1, -1, 0, 0, 1, 1, -1, -1};
    const int dr[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    while (!queue.empty()) {
      const auto [c, i] = queue.top();
      queue.pop();
      if (c > (*cost)[static_cast<size_t>(i)]) continue;
      const int col = i % cols, row = i / cols;
      for (int k = 0; k < 8; ++k) {
        const int nc = col + dc[k], nr = row + dr[k];
        if (nc < 0 || nr < 0 || nc >= cols || nr >= grid.rows()) continue;
        const int j = nr * cols + nc;
        if (!free[static_cast<size_t>(j)]) continue;
        if (k >= 4 && (!free[static_cast<size_t>(row * cols + nc)] || !free[static_cast<size_t>(nr * cols + col)])) continue;
        const double len = (k < 4 ? 1.0 : M_SQRT2) * opt.resolution;
        const double nc_cost = c + len * (1.0 + penalty[static_cast<size_t>(j)]);
        if (nc_cost < (*cost)[static_cast<size_t>(j)]) {
          (*cost)[static_cast<size_t>(j)] = nc_cost;
          (*parent)[static_cast<size_t>(j)] = i;
          queue.push({nc_cost, j});
        }
      }
    }
  }

  bool line_free(const Vec2& a, const Vec2& b) const
  {
    const double len = (b - a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / (opt.resolution * 0.5))));
    for (int k = 0; k <= n; ++k) {
      const int i = grid.index(a + (b - a) * (static_cast<double>(k) / n));
      if (i < 0 || !free[static_cast<size_t>(i)]) return false;
    }
    return true;
  }

  // Line-of-sight smoothing of a cell path into waypoints (excluding the first point).
  std::vector<Vec2> smooth(const std::vector<Vec2>& path) const
  {
    std::vector<Vec2> out;
    size_t i = 0;
    while (i + 1 < path.size()) {
      size_t best = i + 1;
      for (size_t j = i + 2; j < path.size(); ++j) {
        if ((path[j] - path[i]).norm() > opt.max_leg) break;
        if (line_free(path[i], path[j])) best = j;
      }
      out.push_back(path[best]);
      i = best;
    }
    return out;
  }
};

}  // namespace

std::vector<Vec2> laps_route(const Tour& tour, int laps)
{
  std::vector<Vec2> route;
  for (int lap = 0; lap < laps; ++lap)
    route.insert(route.end(), tour.waypoints.begin() + (lap == 0 ? 0 : 1), tour.waypoints.end());
  return route;
}

double polyline_clearance(const World& world, const RobotOptions& robot, const std::vector<Vec2>& polyline)
{
  const Scene scene(world);
  const auto doors = doors_at_start(world);
  const HeightBand band{robot.ground_clearance, robot.height};
  double worst = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k + 1 < polyline.size(); ++k) {
    const Vec2 a = polyline[k], b = polyline[k + 1];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.02)));
    for (int s = 0; s <= n; ++s)
      worst = std::min(worst, scene.clearance(a + (b - a) * (static_cast<double>(s) / n), 2.0, band, doors).distance);
  }
  return worst;
}

std::vector<std::string> regions_along(const World& world, const std::vector<Vec2>& polyline)
{
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (size_t k = 0; k + 1 < polyline.size(); ++k) {
    const Vec2 a = polyline[k], b = polyline[k + 1];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.05)));
    for (int s = 0; s <= n; ++s) {
      const Vec2 p = a + (b - a) * (static_cast<double>(s) / n);
      for (const auto& r : world.regions)
        if (!seen.count(r.name) && point_in_polygon(p, r.polygon)) {
          seen.insert(r.name);
          out.push_back(r.name);
        }
    }
  }
  return out;
}

Tour plan_tour(const World& world, const RobotOptions& robot, const TourOptions& options)
{
  Planner planner(world, robot, options);
  const Grid& grid = planner.grid;
  const int start = grid.index({world.start.x, world.start.y});
  if (start < 0 || !planner.free[static_cast<size_t>(start)])
    throw std::runtime_error(world.name + ": the start pose is not free for a robot of radius " +
                             std::to_string(robot.radius));

  // Goal per region: the reachable cell inside it farthest from obstacles.
  std::vector<double> cost;
  std::vector<int> parent;
  planner.costs_from(start, &cost, &parent);
  struct Goal { std::string name; int cell; };
  std::vector<Goal> goals;
  Tour tour;
  cv::Mat mask(grid.rows(), grid.cols(), CV_8U, cv::Scalar(0));
  for (int i = 0; i < grid.size(); ++i)
    if (planner.free[static_cast<size_t>(i)]) mask.at<uint8_t>(i / grid.cols(), i % grid.cols()) = 255;
  cv::Mat dist;
  cv::distanceTransform(mask, dist, cv::DIST_L2, 5);
  for (const auto& region : world.regions) {
    int best = -1;
    float best_d = -1.f;
    for (int i = 0; i < grid.size(); ++i) {
      if (!std::isfinite(cost[static_cast<size_t>(i)]) || !point_in_polygon(grid.center(i), region.polygon)) continue;
      const float d = dist.at<float>(i / grid.cols(), i % grid.cols());
      if (d > best_d) { best_d = d; best = i; }
    }
    if (best < 0) tour.unreachable.push_back(region.name);
    else goals.push_back({region.name, best});
  }

  // Greedy: always the nearest unvisited goal (regions crossed on the way count as visited).
  std::vector<Vec2> cells_path{grid.center(start)};
  std::vector<Vec2> waypoints{Vec2(world.start.x, world.start.y)};
  std::set<std::string> done;
  int here = start;
  auto append_leg = [&](int goal) {
    std::vector<Vec2> leg;
    for (int c = goal; c != -1; c = parent[static_cast<size_t>(c)]) leg.push_back(grid.center(c));
    std::reverse(leg.begin(), leg.end());
    leg.front() = waypoints.back();
    for (const auto& p : planner.smooth(leg)) waypoints.push_back(p);
    for (const auto& n : regions_along(world, leg)) done.insert(n);
  };
  while (true) {
    int next = -1;
    double next_cost = std::numeric_limits<double>::infinity();
    for (const auto& g : goals)
      if (!done.count(g.name) && cost[static_cast<size_t>(g.cell)] < next_cost) {
        next_cost = cost[static_cast<size_t>(g.cell)];
        next = g.cell;
      }
    if (next < 0) break;
    append_leg(next);
    for (const auto& g : goals)
      if (g.cell == next) done.insert(g.name);
    here = next;
    planner.costs_from(here, &cost, &parent);
  }
  // Back to the start: the tour is a closed loop.
  append_leg(start);
  waypoints.back() = Vec2(world.start.x, world.start.y);

  tour.waypoints = waypoints;
  for (size_t k = 0; k + 1 < waypoints.size(); ++k) tour.length += (waypoints[k + 1] - waypoints[k]).norm();
  tour.visited = regions_along(world, waypoints);
  tour.collision_free = polyline_clearance(world, robot, waypoints) >= robot.radius;
  return tour;
}

std::string tour_to_yaml(const World& world, const Tour& tour)
{
  std::ostringstream o;
  char buf[96];
  o << "# tour through world '" << world.name << "' (sim_tour); closed loop from the start pose\n";
  o << "world: \"" << world.name << "\"\n";
  std::snprintf(buf, sizeof buf, "start: [%.3f, %.3f, %.4f]\n", world.start.x, world.start.y, world.start.theta);
  o << buf;
  std::snprintf(buf, sizeof buf, "length_m: %.2f\n", tour.length);
  o << buf;
  o << "collision_free: " << (tour.collision_free ? "true" : "false") << "\n";
  o << "# waypoints as pairs: [x0, y0, x1, y1, ...] in the world frame [m]\n";
  o << "tour: [";
  for (size_t i = 0; i < tour.waypoints.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%.3f, %.3f", i ? ",\n       " : "", tour.waypoints[i].x(), tour.waypoints[i].y());
    o << buf;
  }
  o << "]\n";
  o << "visited: [";
  for (size_t i = 0; i < tour.visited.size(); ++i) o << (i ? ", " : "") << "\"" << tour.visited[i] << "\"";
  o << "]\n";
  o << "unreachable: [";
  for (size_t i = 0; i < tour.unreachable.size(); ++i) o << (i ? ", " : "") << "\"" << tour.unreachable[i] << "\"";
  o << "]\n";
  return o.str();
}

}  // namespace rgnav::sim
