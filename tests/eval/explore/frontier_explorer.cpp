#include "frontier_explorer.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <deque>
#include <limits>

#include "grid_search.h"

namespace rgnav::explore_eval {

using Eigen::Vector2d;
using geometry::Pose2;
using plan_eval::ConfigSpace;
using plan_eval::GridSearch;
using plan_eval::OccupancyGrid;

namespace {

constexpr int8_t kHit = 2, kMiss = -1, kClamp = 20, kFootprint = -4;

double thread_cpu()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

ScanGrid::ScanGrid(double resolution, double half_extent)
{
  geometry_.resolution = resolution;
  geometry_.origin = Vector2d(-half_extent, -half_extent);
  geometry_.width = geometry_.height = static_cast<int>(std::ceil(2 * half_extent / resolution));
  const size_t n = static_cast<size_t>(geometry_.width) * static_cast<size_t>(geometry_.height);
  log_odds_.assign(n, 0);
  touched_.assign(n, 0);
}

void ScanGrid::touch(const Cell& c)
{
  touched_[geometry_.index(c)] = 1;
  if (max_.x() < min_.x()) {
    min_ = max_ = c;
    return;
  }
  min_ = min_.cwiseMin(c);
  max_ = max_.cwiseMax(c);
}

void ScanGrid::add_scan(const Pose2& map_from_base, const Pose2& base_from_laser, const sensors::LaserScan& scan,
                        double max_range, double robot_radius)
{
  const Pose2 map_from_laser = map_from_base * base_from_laser;
  const Vector2d from = map_from_laser.translation();
  for (size_t b = 0; b < scan.size(); ++b) {
    if (scan.invalid(b)) continue;
    const bool hit = scan.hit(b) && scan.ranges[b] < max_range;
    const double range = hit ? static_cast<double>(scan.ranges[b]) : max_range;
    const Vector2d to = map_from_laser * (range * scan.direction(b));
    for_cells_along(geometry_, from, to, [&](const Cell& c, bool last) {
      if (!geometry_.in_bounds(c)) return true;
      auto& v = log_odds_[geometry_.index(c)];
      v = static_cast<int8_t>(std::clamp<int>(v + (last && hit ? kHit : kMiss), -kClamp, kClamp));
      touch(c);
      return true;
    });
  }
  // The robot stands there.
  const Cell centre = geometry_.cell_of(map_from_base.translation());
  const int r = static_cast<int>(std::ceil(robot_radius / geometry_.resolution));
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      const Cell c(centre.x() + dx, centre.y() + dy);
      if (!geometry_.in_bounds(c) || (geometry_.center_of(c) - map_from_base.translation()).norm() > robot_radius) continue;
      auto& v = log_odds_[geometry_.index(c)];
      v = std::min(v, kFootprint);
      touch(c);
    }
}

uint8_t ScanGrid::state(const Cell& c) const
{
  if (!geometry_.in_bounds(c)) return OccupancyGrid::kUnknown;
  const size_t i = geometry_.index(c);
  if (!touched_[i]) return OccupancyGrid::kUnknown;
  return log_odds_[i] > 0 ? OccupancyGrid::kOccupied : OccupancyGrid::kFree;
}

OccupancyGrid ScanGrid::cropped(int margin, uint8_t unknown_as) const
{
  if (max_.x() < min_.x()) return OccupancyGrid(geometry_.resolution, Vector2d::Zero(), 1, 1);
  const Cell lo = min_ - Cell(margin, margin), hi = max_ + Cell(margin, margin);
  OccupancyGrid g(geometry_.resolution, geometry_.center_of(lo) - Vector2d::Constant(0.5 * geometry_.resolution),
                  hi.x() - lo.x() + 1, hi.y() - lo.y() + 1);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const bool ring = x == 0 || y == 0 || x == g.width - 1 || y == g.height - 1;
      const uint8_t s = state(lo + Cell(x, y));
      g.cells[g.index(Cell(x, y))] = ring ? OccupancyGrid::kUnknown : s == OccupancyGrid::kUnknown ? unknown_as : s;
    }
  return g;
}

std::vector<FrontierCluster> find_frontier_clusters(const OccupancyGrid& grid, int min_cells)
{
  const auto frontier = [&](const Cell& c) {
    if (grid.at(c) != OccupancyGrid::kFree) return false;
    for (const Cell& d : {Cell(1, 0), Cell(-1, 0), Cell(0, 1), Cell(0, -1)})
      if (grid.in_bounds(c + d) && grid.at(c + d) == OccupancyGrid::kUnknown) return true;
    return false;
  };
  std::vector<uint8_t> seen(grid.cells.size(), 0);
  std::vector<FrontierCluster> out;
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const Cell s(x, y);
      if (seen[grid.index(s)] || !frontier(s)) continue;
      FrontierCluster cl;
      std::vector<Cell> open{s};
      seen[grid.index(s)] = 1;
      while (!open.empty()) {
        const Cell c = open.back();
        open.pop_back();
        cl.cells.push_back(c);
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const Cell n(c.x() + dx, c.y() + dy);
            if (!grid.in_bounds(n) || seen[grid.index(n)] || !frontier(n)) continue;
            seen[grid.index(n)] = 1;
            open.push_back(n);
          }
      }
      if (static_cast<int>(cl.cells.size()) < min_cells) continue;
      for (const auto& c : cl.cells) cl.centroid += grid.center_of(c);
      cl.centroid /= static_cast<double>(cl.cells.size());
      out.push_back(std::move(cl));
    }
  return out;
}

struct FrontierExplorer::Space
{
  Space(OccupancyGrid known_grid, OccupancyGrid optimistic, double radius)
      : known(std::move(known_grid)), space(std::move(optimistic), radius), search(space)
  {
  }
  OccupancyGrid known;
  ConfigSpace space;
  GridSearch search;
};

FrontierExplorer::FrontierExplorer(const FrontierOptions& options)
    : options_(options), grid_(options.resolution, options.half_extent)
{
}

FrontierExplorer::~FrontierExplorer() = default;

void FrontierExplorer::add_scan(const Pose2& map_from_base, const Pose2& base_from_laser, const sensors::LaserScan& scan)
{
  const double c0 = thread_cpu();
  grid_.add_scan(map_from_base, base_from_laser, scan, options_.max_range, options_.robot_radius);
  ++scans_;
  cpu_s_ += thread_cpu() - c0;
}

FrontierExplorer::Decision FrontierExplorer::step(double t_s, const Pose2& map_from_base, bool cannot_pass)
{
  Decision d;
  if (!cannot_pass) passable_since_s_ = t_s;
  if (done_ || t_s - last_step_s_ < options_.period_s || scans_ == 0) return d;
  last_step_s_ = t_s;
  const double c0 = thread_cpu();
  OccupancyGrid known = grid_.cropped(3, OccupancyGrid::kUnknown);
  OccupancyGrid optimistic = grid_.cropped(3, OccupancyGrid::kFree);
  space_ = std::make_unique<Space>(std::move(known), std::move(optimistic), options_.robot_radius);
  const OccupancyGrid& g = space_->known;
  const Vector2d robot = map_from_base.translation();
  const int min_cells = static_cast<int>(std::ceil(options_.min_frontier_m / options_.resolution - 1e-9));
  const auto clusters = find_frontier_clusters(g, min_cells);
  // Where the robot fits with the margin; if no frontier is reachable that way (it got into a
  // tight spot), where it fits at all.
  double fit = options_.robot_radius + options_.fit_margin;
  const auto clear_line = [&](const Vector2d& a, const Vector2d& b) {
    bool ok = true;
    for_cells_along(g, a, b, [&](const Cell& c, bool) {
      return ok = space_->space.clearance(c) >= options_.robot_radius + options_.straight_clearance;
    });
    return ok;
  };
  const auto passable = [&](const Cell& c) { return g.at(c) == OccupancyGrid::kFree && space_->space.clearance(c) >= fit; };

  for (int attempt = 0; attempt < 8; ++attempt) {
    // Frontier cells not near a blacklisted goal.
    std::vector<uint8_t> target(g.cells.size(), 0);
    int frontier_cells = 0;
    for (const auto& cl : clusters)
      for (const auto& c : cl.cells) {
        const Vector2d p = g.center_of(c);
        if (std::any_of(blacklist_.begin(), blacklist_.end(),
                        [&](const Vector2d& b) { return (b - p).norm() < options_.blacklist_radius; }))
          continue;
        target[g.index(c)] = 1;
        ++frontier_cells;
      }
    // Breadth-first from the robot over cells it fits in.
    std::optional<Cell> start;
    const Cell rc = g.cell_of(robot);
    if (passable(rc)) start = rc;
    const int reach = static_cast<int>(std::ceil(0.6 / g.resolution));
    for (int r = 1; r <= reach && !start; ++r)
      for (int dy = -r; dy <= r && !start; ++dy)
        for (int dx = -r; dx <= r && !start; ++dx)
          if (std::max(std::abs(dx), std::abs(dy)) == r && passable(rc + Cell(dx, dy))) start = rc + Cell(dx, dy);
    if (!start && fit > options_.robot_radius) {
      fit = options_.robot_radius;
      --attempt;
      continue;
    }
    if (!start) {
      activity_ = "robot not on free space it fits in";
      break;
    }
    // The running goal stays while frontier cells are left near it.
    std::optional<Cell> goal_cell;
    if (goal_) {
      const Cell gc = g.cell_of(*goal_);
      const int r = static_cast<int>(std::ceil(options_.blacklist_radius / g.resolution));
      for (int dy = -r; dy <= r && !goal_cell; ++dy)
        for (int dx = -r; dx <= r && !goal_cell; ++dx)
          if (g.in_bounds(gc + Cell(dx, dy)) && target[g.index(gc + Cell(dx, dy))]) goal_cell = gc;
    }
    std::vector<uint8_t> visited(g.cells.size(), 0);
    std::deque<Cell> open{*start};
    visited[g.index(*start)] = 1;
    while (!goal_cell && !open.empty()) {
      const Cell c = open.front();
      open.pop_front();
      if (target[g.index(c)]) {
        goal_cell = c;
        break;
      }
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Cell n(c.x() + dx, c.y() + dy);
          if ((dx == 0 && dy == 0) || !g.in_bounds(n) || visited[g.index(n)] || !passable(n)) continue;
          visited[g.index(n)] = 1;
          open.push_back(n);
        }
    }
    if (!goal_cell && fit > options_.robot_radius) {
      fit = options_.robot_radius;
      --attempt;
      continue;
    }
    if (!goal_cell) {
      done_ = true;
      activity_ = "done: no reachable frontier (" + std::to_string(frontier_cells) + " frontier cells left, " +
                  std::to_string(blacklist_.size()) + " goals blacklisted)";
      break;
    }
    const Vector2d goal = goal_ && g.cell_of(*goal_) == *goal_cell ? *goal_ : g.center_of(*goal_cell);
    if (!goal_ || (goal - *goal_).norm() > 1e-9) {
      goal_ = goal;
      ++goal_id_;
      ++goals_;
      best_distance_ = std::numeric_limits<double>::infinity();
      progress_s_ = passable_since_s_ = t_s;
    }
    // Reached, and the frontier is still there: it cannot be seen from here. Or collision
    // avoidance cannot get nearer.
    const bool stuck = (robot - *goal_).norm() <= options_.stuck_distance_m && t_s - passable_since_s_ > options_.stuck_near_goal_s;
    if ((robot - *goal_).norm() <= options_.goal_reached_m || stuck) {
      blacklist_.push_back(*goal_);
      goal_.reset();
      continue;
    }
    const auto path = space_->search.wall_cost_astar(robot, *goal_, 0.6, plan_eval::WallCost{});
    if (!path) {
      ++no_path_;
      blacklist_.push_back(*goal_);
      goal_.reset();
      continue;
    }
    if (path->length < best_distance_ - options_.progress_m) {
      best_distance_ = path->length;
      progress_s_ = t_s;
    } else if (t_s - progress_s_ > options_.progress_timeout_s) {
      blacklist_.push_back(*goal_);
      goal_.reset();
      continue;
    }
    // Targets: the path straightened where the straight line keeps collision avoidance's margin
    // (straight_clearance) from what the grid knows as occupied, then cut
    // into pieces no longer than target_spacing; headings along the path.
    std::vector<Vector2d> corners{path->points.front()};
    size_t k = 0;
    while (k + 1 < path->points.size()) {
      size_t far = k + 1;
      for (size_t j = k + 2; j < std::min(path->points.size(), k + 40); ++j)
        if (clear_line(path->points[k], path->points[j])) far = j;
      corners.push_back(path->points[far]);
      k = far;
    }
    std::vector<Vector2d> pts;
    for (size_t i = 1; i < corners.size(); ++i) {
      const Vector2d a = corners[i - 1], b = corners[i];
      const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / options_.target_spacing)));
      for (int s = 1; s <= n; ++s) pts.push_back(a + (b - a) * (static_cast<double>(s) / n));
    }
    if (pts.empty()) pts.push_back(*goal_);
    Vector2d prev = robot;
    for (const auto& p : pts) {
      const Vector2d dir = p - prev;
      const double heading = dir.norm() > 1e-6 ? std::atan2(dir.y(), dir.x()) : map_from_base.theta();
      d.map_targets.emplace_back(p, heading);
      prev = p;
    }
    d.new_targets = true;
    d.goal_id = goal_id_;
    activity_ = "frontier goal " + std::to_string(goal_id_) + " at " + std::to_string(goal_->x()) + "," +
                std::to_string(goal_->y()) + " path " + std::to_string(path->length) + " m";
    break;
  }
  cpu_s_ += thread_cpu() - c0;
  return d;
}

}  // namespace rgnav::explore_eval
