#include "collision_avoidance/give_way.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "collision_avoidance/chain_planner.h"
#include "collision_avoidance/local_grid.h"

namespace rgnav::collision_avoidance {

double PersonPath::distance(const Eigen::Vector2d& p) const
{
  const double s = std::max(0.0, along(p));
  return (p - (from + s * direction)).norm();
}

namespace {

// Corners along the search's cells (`cells.front()` the robot) whose straight legs keep what
// first_collision asks of a chain from the robot: the clearance (plus `margin`, for what the
// scans add on the way), or where the robot starts closer than that to something (the person
// who walked up), growing as it leaves. Each leg is grown from its corner as far along the
// cells as it stays free.
std::vector<Eigen::Vector2d> leaving_corners(const LocalMap& map, const std::vector<Eigen::Vector2d>& cells,
                                             double clearance, double margin)
{
  const double c0 = map.clearance(cells.front(), clearance);
  auto leg_free = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double s0, double need) {
    const double len = (b - a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / 0.05)));
    for (int i = 1; i <= n; ++i) {
      const double f = static_cast<double>(i) / n;
      if (map.clearance(a + (b - a) * f, need) < required_clearance(need, c0, s0 + f * len) - 1e-9) return false;
    }
    return true;
  };
  std::vector<Eigen::Vector2d> corners;
  size_t i = 0;
  double s = 0.0;  // arc length to cells[i] along the corners so far
  while (i + 1 < cells.size()) {
    size_t best = i + 1;  // the search's own step is trusted when nothing longer is free
    for (size_t j = i + 2; j < cells.size() && leg_free(cells[i], cells[j], s, clearance + margin); ++j) best = j;
    // Between walls closer than that (a narrow hallway), straight legs keep the plain clearance:
    // the grid's steps zigzag from cell to cell, and a drive cannot stop and turn at each.
    if (best == i + 1)
      for (size_t j = i + 2; j < cells.size() && leg_free(cells[i], cells[j], s, clearance); ++j) best = j;
    s += (cells[best] - cells[i]).norm();
    corners.push_back(cells[best]);
    i = best;
  }
  return corners;
}

}  // namespace

namespace {

// A search over the local map's grid from the robot (Dijkstra, 8-connected) through space the
// scans saw (not out of every view, but for the robot's own surroundings) to the cheapest cell
// `goal` accepts within `max_travel` of way; `allowed` may close cells, `factor` weighs steps
// (from, to). Where the robot starts closer than the clearance to something, the way may leave,
// as first_collision lets a chain, never get closer. Cells below clearance + way_margin cost
// more where there is room. The way: cell centres from the robot (first) to the goal cell.
using CellTest = std::function<bool(int x, int y, const Eigen::Vector2d& centre)>;
using StepFactor = std::function<double(const Eigen::Vector2d& from, const Eigen::Vector2d& to)>;
std::optional<std::vector<Eigen::Vector2d>> search(const LocalMap& map, const LocalGrid& grid, const Eigen::Vector2d& robot,
                                                   double clearance, const YieldOptions& o, double max_travel,
                                                   const CellTest& allowed, const CellTest& goal, const StepFactor& factor)
{
  const int w = grid.width(), h = grid.height();
  const Eigen::Vector2i s = grid.cell_of(robot);
  const double c0 = map.clearance(robot, clearance);
  // `from`: where the step into the cell starts (the robot, or a cell's centre); `len`: the
  // way's length to the cell.
  auto passable = [&](int x, int y, const Eigen::Vector2d& from, double len) {
    const Eigen::Vector2d c = grid.centre(x, y);
    if (!grid.in_view(x, y) && (c - robot).norm() > 0.5) return false;  // unknown: behind the robot
    if (!allowed(x, y, c)) return false;
    if (grid.clearance(x, y) >= clearance) return true;  // the grid's is on the safe side
    const double step = (c - from).norm();
    for (const double f : {0.5, 1.0})
      if (map.clearance(from + f * (c - from), clearance) < required_clearance(clearance, c0, len - (1.0 - f) * step) + 0.01)
        return false;
    return true;
  };
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  std::vector<double> cost(n, std::numeric_limits<double>::infinity()), length(n, 0.0);
  std::vector<int> parent(n, -1);
  std::vector<uint8_t> closed(n, 0);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const int start = grid.index(s.x(), s.y());
  cost[static_cast<size_t>(start)] = 0.0;
  open.emplace(0.0, start);
  int found = -1;
  while (!open.empty()) {
    const int cur = open.top().second;
    open.pop();
    if (closed[static_cast<size_t>(cur)]) continue;
    closed[static_cast<size_t>(cur)] = 1;
    const int cx = cur % w, cy = cur / w;
    if (goal(cx, cy, grid.centre(cx, cy))) {
      found = cur;
      break;
    }
    const Eigen::Vector2d here = cur == start ? robot : grid.centre(cx, cy);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int nx = cx + dx, ny = cy + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const int ni = grid.index(nx, ny);
        if (closed[static_cast<size_t>(ni)]) continue;
        const Eigen::Vector2d next = grid.centre(nx, ny);
        const double step = (next - here).norm();
        const double len = length[static_cast<size_t>(cur)] + step;
        if (len > max_travel || !passable(nx, ny, here, len)) continue;
        double f = factor(here, next);
        // Keep way_margin more than the clearance where there is room (between walls that close
        // in, it cannot: a narrow hallway stays passable).
        if (o.way_margin > 0.0)
          f *= 1.0 + 2.0 * std::clamp((clearance + o.way_margin - grid.clearance(nx, ny)) / o.way_margin, 0.0, 1.0);
        const double c = cost[static_cast<size_t>(cur)] + step * f;
        if (c < cost[static_cast<size_t>(ni)]) {
          cost[static_cast<size_t>(ni)] = c;
          length[static_cast<size_t>(ni)] = len;
          parent[static_cast<size_t>(ni)] = cur;
          open.emplace(c, ni);
        }
      }
  }
  if (found < 0) return std::nullopt;
  std::vector<Eigen::Vector2d> cells;
  for (int i = found; i >= 0; i = parent[static_cast<size_t>(i)]) cells.push_back(grid.centre(i % w, i / w));
  std::reverse(cells.begin(), cells.end());
  cells.front() = robot;
  return cells;
}

double length_of(const Eigen::Vector2d& from, const std::vector<Eigen::Vector2d>& corners)
{
  double l = 0.0;
  Eigen::Vector2d prev = from;
  for (const auto& c : corners) {
    l += (c - prev).norm();
    prev = c;
  }
  return l;
}

constexpr double kAheadOfThem = 0.5;  // [m] a yield point lies at least this far ahead of the person along their path

}  // namespace

std::optional<YieldPoint> choose_yield_point(const LocalMap& map, const Eigen::Vector2d& robot, const PersonPath& path,
                                             double clearance, const YieldOptions& o)
{
  const double reach = o.max_travel + 0.5;
  const LocalGrid grid(map, robot.array() - reach, robot.array() + reach, o.cell);
  const double off_needed = clearance + o.path_half_width + o.extra;
  // Never nearer the person than clearance + person_keep, nor nearer than the robot is now.
  const double keep = std::min(clearance + o.person_keep, (robot - path.from).norm());
  const auto cells = search(
      map, grid, robot, clearance, o, o.max_travel,
      [&](int, int, const Eigen::Vector2d& c) { return (c - path.from).norm() >= keep; },
      // In view: seen free, or in the shadow of what was seen (from inside a hallway, the room
      // beyond its mouth is seen only through the mouth; the way there is re-chosen as it opens).
      // And ahead of the person along their path: not beside or past them (that is their side).
      [&](int x, int y, const Eigen::Vector2d& c) {
        return grid.in_view(x, y) && grid.clearance(x, y) >= clearance + o.spot_margin && path.distance(c) >= off_needed &&
               path.along(c) >= kAheadOfThem;
      },
      // Leave the person's path at once, and not down it farther than needed (give_way.h);
      // through space the scans saw rather than its shadow.
      [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
        double f = path.distance(to) < clearance + o.path_half_width ? o.in_path_cost : 1.0;
        if ((to - from).dot(path.direction) > 0.3 * (to - from).norm()) f *= o.downstream_cost;
        const Eigen::Vector2i c = grid.cell_of(to);
        if (!grid.seen(c.x(), c.y())) f *= o.shadow_cost;
        return f;
      });
  if (!cells) return std::nullopt;
  YieldPoint y;
  y.point = cells->back();
  y.off_path = path.distance(y.point);
  if (cells->size() < 2) return y;  // already out of the way
  y.corners = leaving_corners(map, *cells, clearance, o.way_margin);
  y.travel = length_of(robot, y.corners);
  return y;
}

std::optional<std::vector<Eigen::Vector2d>> way_to(const LocalMap& map, const Eigen::Vector2d& robot,
                                                   const Eigen::Vector2d& to, double clearance, const YieldOptions& o)
{
  const double reach = o.max_travel + 0.5;
  if ((to - robot).norm() > reach) return std::nullopt;
  const LocalGrid grid(map, robot.array() - reach, robot.array() + reach, o.cell);
  const Eigen::Vector2i g = grid.cell_of(to);
  const auto cells = search(
      map, grid, robot, clearance, o, 2.0 * o.max_travel, [](int, int, const Eigen::Vector2d&) { return true; },
      [&](int x, int y, const Eigen::Vector2d&) { return x == g.x() && y == g.y(); },
      [](const Eigen::Vector2d&, const Eigen::Vector2d&) { return 1.0; });
  if (!cells || cells->size() < 2) return std::nullopt;
  std::vector<Eigen::Vector2d> points = *cells;
  points.back() = to;
  return leaving_corners(map, points, clearance, o.way_margin);
}

ToPass someone_to_pass(const LocalMap& map, const PersonPath& path, const Eigen::Vector2d& robot, const YieldOptions& o)
{
  const double robot_along = path.along(robot);
  auto watched = [&](const Eigen::Vector2d& p) {
    const double a = path.along(p);
    const Eigen::Vector2d d = p - path.from;
    const double lateral = std::fabs(d.x() * path.direction.y() - d.y() * path.direction.x());
    return a >= -o.watch_behind && a <= robot_along && lateral <= o.watch_half_width;
  };
  // Walking: only tracks that moved count (a wall face coming into view as the robot turns is
  // young too, but does not move); someone who turned back walks away along the path.
  for (const Track& t : map.tracker().tracks()) {
    if (!t.moved || t.moving_steady <= 0.0 || t.centroids.empty() || !watched(t.centroids.back().second)) continue;
    if (t.velocity.dot(path.direction) < -0.2) continue;
    return ToPass::kWalking;
  }
  // Standing: a mover that stopped, and something still stands where it did (the newest scan
  // does not look through its place; out of view, what the map remembers there).
  // In view, they stand apart from what is behind them (a piece of wall a person walking past
  // hid for a moment reappears like someone who walked and stopped).
  constexpr double kPersonRadius = 0.3, kApart = 0.3;
  for (const auto& m : map.tracker().last_seen_movers()) {
    if (m.moving_steady <= 0.0 || !watched(m.position) || map.clearance(m.position, kPersonRadius) >= kPersonRadius) continue;
    const SeenNow seen = map.seen_now(m.position);
    if (seen == SeenNow::kFreeNow || (seen == SeenNow::kStillThere && !map.stands_apart(m.position, kPersonRadius, kApart)))
      continue;
    return ToPass::kStanding;
  }
  return ToPass::kNobody;
}

std::optional<OneLane> one_lane_between(const LocalMap& map, const Eigen::Vector2d& robot, const Eigen::Vector2d& person,
                                        double width, double person_radius)
{
  const Eigen::Vector2d d = person - robot;
  const double length = d.norm() - person_radius;
  if (length <= 0.0) return std::nullopt;
  return one_lane_along(map, robot, robot + d.normalized() * length, width, person, person_radius + 0.15);
}

std::optional<OneLane> one_lane_along(const LocalMap& map, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                      double width, const Eigen::Vector2d& exclude, double exclude_radius)
{
  constexpr double kStep = 0.1;  // [m] places along the line
  const Eigen::Vector2d d = to - from;
  const double length = d.norm();
  if (length <= 1e-9) return std::nullopt;
  const Eigen::Vector2d u = d.normalized(), n(-u.y(), u.x());
  const int samples = static_cast<int>(std::floor(length / kStep)) + 1;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> left(static_cast<size_t>(samples), inf), right(static_cast<size_t>(samples), inf);
  for (size_t k = 0; k < map.points().size(); ++k) {
    const Eigen::Vector2d& p = map.points()[k];
    if (map.predicted_only(k) || (p - exclude).norm() < exclude_radius) continue;
    const Eigen::Vector2d r = p - from;
    const double along = r.dot(u), lateral = r.dot(n);
    if (std::fabs(lateral) >= width || along < -kOneLaneSlab || along > length + kOneLaneSlab) continue;
    const int lo = std::max(0, static_cast<int>(std::ceil((along - kOneLaneSlab) / kStep - 1e-9)));
    const int hi = std::min(samples - 1, static_cast<int>(std::floor((along + kOneLaneSlab) / kStep + 1e-9)));
    for (int i = lo; i <= hi; ++i) {
      auto& side = lateral >= 0.0 ? left[static_cast<size_t>(i)] : right[static_cast<size_t>(i)];
      side = std::min(side, std::fabs(lateral));
    }
  }
  // A wall seen at a grazing angle: its points lie farther apart than the slabs are wide. Where
  // a side has none, what it has within kOneLaneBridge either way (the wider) bridges the gap.
  for (auto* side : {&left, &right}) {
    const int reach = static_cast<int>(std::round(kOneLaneBridge / kStep));
    const std::vector<double> seen = *side;
    for (int i = 0; i < samples; ++i) {
      if (std::isfinite(seen[static_cast<size_t>(i)])) continue;
      double before = inf, after = inf;
      for (int k = i - 1; k >= std::max(0, i - reach) && !std::isfinite(before); --k) before = seen[static_cast<size_t>(k)];
      for (int k = i + 1; k <= std::min(samples - 1, i + reach) && !std::isfinite(after); ++k) after = seen[static_cast<size_t>(k)];
      if (std::isfinite(before) && std::isfinite(after)) (*side)[static_cast<size_t>(i)] = std::max(before, after);
    }
  }
  std::optional<OneLane> lane;
  for (int i = 0; i < samples; ++i) {
    if (left[static_cast<size_t>(i)] + right[static_cast<size_t>(i)] >= width) continue;
    const double s = std::min(length, i * kStep);
    if (!lane) lane = OneLane{s, s, length};
    lane->end = s;
  }
  return lane;
}

std::optional<GiveWay> choose_give_way(const LocalMap& map, const Eigen::Vector2d& from, double away, double clearance,
                                       double step, const GiveWayOptions& o)
{
  std::optional<GiveWay> best;
  double best_score = 0.0;
  const int n = std::max(1, o.headings);
  for (int k = 0; k < n; ++k) {
    // Straight back first, then alternating outward, so ties keep the most direct heading.
    const int i = (k + 1) / 2 * (k % 2 ? 1 : -1);
    const double dev = n > 1 ? o.spread * i / ((n - 1) / 2.0) : 0.0;
    if (std::fabs(dev) > o.spread + 1e-9) continue;
    const double heading = geometry::normalize_angle(away + dev);
    const trajectory::Chain line({trajectory::Segment::line(Pose2(from, heading), o.length)});
    double free = o.length;
    if (const auto hit = first_collision(line, map, clearance, step)) free = *hit - step;
    if (free < o.min_length) continue;
    const double score = free * (0.5 + 0.5 * std::cos(dev));  // sideways counts half
    if (score > best_score + 1e-9) {
      best_score = score;
      best = GiveWay{heading, free};
    }
  }
  return best;
}

}  // namespace rgnav::collision_avoidance
