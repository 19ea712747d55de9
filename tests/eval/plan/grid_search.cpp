#include "grid_search.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <queue>
#include <utility>

namespace rgnav::plan_eval {

using Eigen::Vector2d;

namespace {

struct Move
{
  int dx, dy;
  float length;   // [cells]
};

const std::vector<Move>& moves(bool sixteen)
{
  static const std::vector<Move> eight = [] {
    std::vector<Move> m;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx || dy) m.push_back({dx, dy, static_cast<float>(std::hypot(dx, dy))});
    return m;
  }();
  static const std::vector<Move> all = [] {
    std::vector<Move> m = eight;
    for (int a : {-1, 1})
      for (int b : {-2, 2}) {
        m.push_back({a, b, static_cast<float>(std::sqrt(5.0))});
        m.push_back({b, a, static_cast<float>(std::sqrt(5.0))});
      }
    return m;
  }();
  return sixteen ? all : eight;
}

double polyline_length(const std::vector<Vector2d>& p)
{
  double l = 0;
  for (size_t k = 1; k < p.size(); ++k) l += (p[k] - p[k - 1]).norm();
  return l;
}

}  // namespace

double WallCost::factor(double clearance, double radius) const
{
  const double d = clearance - radius;
  if (d >= margin + comfort) return 1.0;
  if (d >= margin) return 1.0 + comfort_cost;
  const double share = margin > 0 ? std::clamp(1.0 - d / margin, 0.0, 1.0) : 1.0;
  return 1.0 + comfort_cost + (wall_cost - comfort_cost) * share;
}

GridSearch::GridSearch(const ConfigSpace& space) : space_(space)
{
  const size_t n = space_.grid().cells.size();
  g_.assign(n, 0.0f);
  parent_.assign(n, -1);
  stamp_.assign(n, 0);
  closed_.assign(n, 0);
}

std::optional<std::vector<Cell>> GridSearch::astar(const Cell& start, const Cell& goal, bool sixteen,
                                                   const std::vector<float>* weight, int* expanded, bool use_heuristic)
{
  const auto& grid = space_.grid();
  const int w = grid.width;
  ++query_;
  const auto idx = [&](const Cell& c) { return static_cast<int32_t>(grid.index(c)); };
  const auto heuristic = [&](const Cell& c) {
    if (!use_heuristic) return 0.0f;
    const double dx = std::abs(c.x() - goal.x()), dy = std::abs(c.y() - goal.y());
    // Octile distance for 8 neighbours, Euclidean for 16 (both admissible: weights are >= 1).
    return static_cast<float>(sixteen ? std::hypot(dx, dy) : std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy));
  };
  using Entry = std::pair<float, int32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const int32_t s = idx(start), t = idx(goal);
  g_[s] = 0;
  parent_[s] = -1;
  stamp_[s] = query_;
  open.push({heuristic(start), s});
  int n_expanded = 0;
  const auto& mv = moves(sixteen);
  bool found = false;
  while (!open.empty()) {
    const int32_t i = open.top().second;
    open.pop();
    if (closed_[i] == query_) continue;
    closed_[i] = query_;
    ++n_expanded;
    if (i == t) {
      found = true;
      break;
    }
    const Cell c(i % w, i / w);
    for (const Move& m : mv) {
      const Cell n(c.x() + m.dx, c.y() + m.dy);
      if (!space_.free(n)) continue;
      // No corner cutting: the cells the straight step passes must be free too.
      if (m.dx && m.dy) {
        const int sx = m.dx > 0 ? 1 : -1, sy = m.dy > 0 ? 1 : -1;
        if (std::abs(m.dx) == 1 && std::abs(m.dy) == 1) {
          if (!space_.free(Cell(c.x() + m.dx, c.y())) || !space_.free(Cell(c.x(), c.y() + m.dy))) continue;
        } else if (std::abs(m.dy) == 2) {
          if (!space_.free(Cell(c.x(), c.y() + sy)) || !space_.free(Cell(c.x() + m.dx, c.y() + sy))) continue;
        } else {
          if (!space_.free(Cell(c.x() + sx, c.y())) || !space_.free(Cell(c.x() + sx, c.y() + m.dy))) continue;
        }
      }
      const int32_t j = idx(n);
      if (closed_[j] == query_) continue;
      float step = m.length;
      if (weight) step *= 0.5f * ((*weight)[i] + (*weight)[j]);
      const float gj = g_[i] + step;
      if (stamp_[j] == query_ && g_[j] <= gj) continue;
      stamp_[j] = query_;
      g_[j] = gj;
      parent_[j] = i;
      open.push({gj + heuristic(n), j});
    }
  }
  if (expanded) *expanded = n_expanded;
  if (!found) return std::nullopt;
  std::vector<Cell> path;
  for (int32_t i = t; i >= 0; i = parent_[i]) path.push_back(Cell(i % w, i / w));
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<Vector2d> GridSearch::pull_string(const std::vector<Vector2d>& p) const
{
  // Greedy: from each anchor, the farthest later point in sight; a few points out of sight are
  // looked past (a line grazing a corner may be blocked for one cell and free again after it).
  constexpr int kLookPast = 12;
  std::vector<Vector2d> out;
  if (p.empty()) return out;
  out.push_back(p.front());
  size_t anchor = 0;
  while (anchor + 1 < p.size()) {
    size_t best = anchor + 1;
    int misses = 0;
    for (size_t k = anchor + 1; k < p.size(); ++k) {
      if (space_.line_free(p[anchor], p[k])) {
        best = k;
        misses = 0;
      } else if (++misses > kLookPast) {
        break;
      }
    }
    out.push_back(p[best]);
    anchor = best;
  }
  return out;
}

std::vector<Vector2d> GridSearch::tighten(std::vector<Vector2d> p) const
{
  // String pulling leaves its turns on cell centres of the grid path, up to a cell or two off
  // the obstacle it bends round. Each turn is cut as far as the line of sight allows (the same
  // share of both its legs, found by bisection), the result pulled again, until a pass gains
  // less than a millimetre.
  for (int pass = 0; pass < 20 && p.size() > 2; ++pass) {
    const double before = polyline_length(p);
    std::vector<Vector2d> cut{p.front()};
    for (size_t i = 1; i + 1 < p.size(); ++i) {
      const Vector2d& v = p[i];
      const Vector2d to_prev = cut.back() - v, to_next = p[i + 1] - v;
      double lo = 0, hi = 0.5;
      for (int k = 0; k < 12; ++k) {
        const double t = 0.5 * (lo + hi);
        (space_.line_free(v + t * to_prev, v + t * to_next) ? lo : hi) = t;
      }
      if (lo * std::min(to_prev.norm(), to_next.norm()) < 1e-3) {
        cut.push_back(v);
      } else {
        cut.push_back(v + lo * to_prev);
        cut.push_back(v + lo * to_next);
      }
    }
    cut.push_back(p.back());
    p = pull_string(cut);
    if (before - polyline_length(p) < 1e-3) break;
  }
  return p;
}

std::optional<GridPath> GridSearch::shortest(const Vector2d& from, const Vector2d& to, double adapt_distance)
{
  const auto& grid = space_.grid();
  const auto ends = adapted_ends(from, to, adapt_distance);
  if (!ends) return std::nullopt;
  const auto [s, t] = *ends;
  int expanded = 0;
  const auto cells = astar(s, t, true, nullptr, &expanded);
  if (!cells) return std::nullopt;
  std::vector<Vector2d> pts;
  for (const auto& c : *cells) pts.push_back(grid.center_of(c));
  // The exact ends where the robot may stand there.
  if (s == grid.cell_of(from)) pts.front() = from;
  if (t == grid.cell_of(to)) pts.back() = to;
  if (pts.size() == 1) pts.push_back(pts.front());
  auto forward = pull_string(pts);
  std::vector<Vector2d> rev(pts.rbegin(), pts.rend());
  auto backward = pull_string(rev);
  std::reverse(backward.begin(), backward.end());
  GridPath out;
  out.points = tighten(polyline_length(backward) < polyline_length(forward) ? backward : forward);
  out.length = polyline_length(out.points);
  out.cost = out.length;
  out.expanded = expanded;
  return out;
}

std::optional<GridPath> GridSearch::wall_cost_astar(const Vector2d& from, const Vector2d& to, double adapt_distance,
                                                    const WallCost& cost, bool heuristic)
{
  const auto& grid = space_.grid();
  if (wall_weight_.empty() || wall_weight_for_.margin != cost.margin || wall_weight_for_.comfort != cost.comfort ||
      wall_weight_for_.wall_cost != cost.wall_cost || wall_weight_for_.comfort_cost != cost.comfort_cost) {
    // The costmap is built once per grid, as a NavFn-style planner keeps its costmap.
    wall_weight_.resize(grid.cells.size());
    for (size_t i = 0; i < grid.cells.size(); ++i) {
      const Cell c(static_cast<int>(i % grid.width), static_cast<int>(i / grid.width));
      wall_weight_[i] = static_cast<float>(cost.factor(space_.clearance(c), space_.robot_radius()));
    }
    wall_weight_for_ = cost;
  }
  const auto ends = adapted_ends(from, to, adapt_distance);
  if (!ends) return std::nullopt;
  const auto [s, t] = *ends;
  int expanded = 0;
  const auto cells = astar(s, t, false, &wall_weight_, &expanded, heuristic);
  if (!cells) return std::nullopt;
  GridPath out;
  for (const auto& c : *cells) out.points.push_back(grid.center_of(c));
  if (s == grid.cell_of(from)) out.points.front() = from;
  if (t == grid.cell_of(to)) out.points.back() = to;
  out.length = polyline_length(out.points);
  const int32_t goal = static_cast<int32_t>(grid.index(t));
  out.cost = g_[goal] * grid.resolution;
  out.expanded = expanded;
  return out;
}

bool GridSearch::connected(const Vector2d& from, const Vector2d& to, double adapt_distance)
{
  return adapted_ends(from, to, adapt_distance).has_value();
}

std::optional<std::pair<Cell, Cell>> GridSearch::adapted_ends(const Vector2d& from, const Vector2d& to, double adapt_distance)
{
  if (!components_) components_.emplace(space_, space_.robot_radius());
  const auto& grid = space_.grid();
  // Per component, the nearest free cell within reach of each end; the joined pair with the
  // smallest total move wins (the nearest free cell may lie in a pocket cut off from the rest).
  const auto candidates = [&](const Vector2d& p) {
    std::map<int32_t, std::pair<double, Cell>> best;
    const Cell c = grid.cell_of(p);
    const int r = static_cast<int>(std::ceil(adapt_distance / grid.resolution));
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const double d = std::hypot(dx, dy) * grid.resolution;
        if (d > adapt_distance + 1e-9) continue;
        const Cell n(c.x() + dx, c.y() + dy);
        const int32_t label = components_->label(n);
        if (label < 0) continue;
        auto it = best.find(label);
        if (it == best.end() || d < it->second.first) best[label] = {d, n};
      }
    return best;
  };
  const auto a = candidates(from), b = candidates(to);
  std::optional<std::pair<Cell, Cell>> out;
  double best = INFINITY;
  for (const auto& [label, da] : a) {
    const auto it = b.find(label);
    if (it != b.end() && da.first + it->second.first < best) {
      best = da.first + it->second.first;
      out = std::make_pair(da.second, it->second.second);
    }
  }
  return out;
}

Components::Components(const ConfigSpace& space, double min_clearance) : space_(space), min_clearance_(min_clearance)
{
  const auto& grid = space_.grid();
  label_.assign(grid.cells.size(), -1);
  const auto in_set = [&](const Cell& c) { return grid.in_bounds(c) && space_.clearance(c) >= min_clearance_; };
  int32_t next = 0;
  std::deque<Cell> q;
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const Cell c0(x, y);
      if (!in_set(c0) || label_[grid.index(c0)] >= 0) continue;
      label_[grid.index(c0)] = next;
      q.push_back(c0);
      while (!q.empty()) {
        const Cell c = q.front();
        q.pop_front();
        for (const Cell& d : {Cell(1, 0), Cell(-1, 0), Cell(0, 1), Cell(0, -1)}) {
          const Cell n = c + d;
          if (in_set(n) && label_[grid.index(n)] < 0) {
            label_[grid.index(n)] = next;
            q.push_back(n);
          }
        }
      }
      ++next;
    }
}

int32_t Components::label(const Cell& c) const
{
  return space_.grid().in_bounds(c) ? label_[space_.grid().index(c)] : -1;
}

std::optional<Cell> Components::nearest(const Cell& c, double max_distance) const
{
  if (label(c) >= 0) return c;
  const int r = static_cast<int>(std::ceil(max_distance / space_.grid().resolution));
  std::optional<Cell> best;
  int best_d2 = r * r + 1;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      const int d2 = dx * dx + dy * dy;
      const Cell n(c.x() + dx, c.y() + dy);
      if (d2 < best_d2 && label(n) >= 0) {
        best = n;
        best_d2 = d2;
      }
    }
  return best;
}

bool Components::joined(const Vector2d& a, const Vector2d& b, double max_distance) const
{
  const auto ca = nearest(space_.grid().cell_of(a), max_distance), cb = nearest(space_.grid().cell_of(b), max_distance);
  return ca && cb && label(*ca) == label(*cb);
}

}  // namespace rgnav::plan_eval
