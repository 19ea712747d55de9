#include "planner/framed_quadtree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace rgnav::planner {

FramedQuadtree::FramedQuadtree(const RegionGrid& grid, int max_quad_cells)
    : grid_(grid), max_quad_(std::max(1, max_quad_cells))
{
  quad_of_cell_.assign(static_cast<size_t>(grid.width()) * grid.height(), -1);
  int root = 1;
  while (root < std::max(grid.width(), grid.height())) root *= 2;
  build(0, 0, root);
}

void FramedQuadtree::build(int x0, int y0, int size)
{
  if (x0 >= grid_.width() || y0 >= grid_.height()) return;
  const bool inside = x0 + size <= grid_.width() && y0 + size <= grid_.height();
  bool uniform = inside;
  const uint8_t level = grid_.level(Cell(x0, y0));
  if (uniform) {
    for (int y = y0; y < y0 + size && uniform; ++y)
      for (int x = x0; x < x0 + size && uniform; ++x) uniform = grid_.level(Cell(x, y)) == level;
  }
  if (uniform && (size <= max_quad_ || level == RegionGrid::kBlocked)) {
    if (level == RegionGrid::kBlocked) return;
    const int q = static_cast<int>(quads_.size());
    quads_.push_back({x0, y0, size, level});
    for (int y = y0; y < y0 + size; ++y)
      for (int x = x0; x < x0 + size; ++x) quad_of_cell_[static_cast<size_t>(y) * grid_.width() + x] = q;
    return;
  }
  const int h = size / 2;
  build(x0, y0, h);
  build(x0 + h, y0, h);
  build(x0, y0 + h, h);
  build(x0 + h, y0 + h, h);
}

int FramedQuadtree::quad_at(const Cell& c) const
{
  if (!grid_.in_bounds(c)) return -1;
  return quad_of_cell_[static_cast<size_t>(c.y()) * grid_.width() + c.x()];
}

void FramedQuadtree::border_cells(int q, std::vector<Cell>* out) const
{
  out->clear();
  const Quad& d = quads_[static_cast<size_t>(q)];
  const int x1 = d.x0 + d.size - 1, y1 = d.y0 + d.size - 1;
  if (d.size == 1) {
    out->push_back(Cell(d.x0, d.y0));
    return;
  }
  for (int x = d.x0; x <= x1; ++x) {
    out->push_back(Cell(x, d.y0));
    out->push_back(Cell(x, y1));
  }
  for (int y = d.y0 + 1; y < y1; ++y) {
    out->push_back(Cell(d.x0, y));
    out->push_back(Cell(x1, y));
  }
}

std::optional<std::vector<Cell>> FramedQuadtree::search(const Cell& start, const Cell& goal, QuadSearchStats* stats) const
{
  const int qs = quad_at(start), qg = quad_at(goal);
  if (stats) *stats = {0, static_cast<int>(quads_.size())};
  if (qs < 0 || qg < 0) return std::nullopt;
  const int w = grid_.width();
  const auto idx = [w](const Cell& c) { return c.y() * w + c.x(); };
  const auto cell = [w](int i) { return Cell(i % w, i / w); };
  const auto dist = [](const Cell& a, const Cell& b) { return static_cast<float>((a - b).cast<double>().norm()); };

  // Scratch kept between searches; a cell's entries count only when stamped with this search
  // (no clearing of grid-sized arrays per search).
  const size_t n = static_cast<size_t>(w) * grid_.height();
  if (scratch_.stamp.size() != n) scratch_ = Scratch{std::vector<uint32_t>(n, 0), std::vector<float>(n), std::vector<int>(n), std::vector<uint8_t>(n), 0};
  const uint32_t id = ++scratch_.search;
  auto& stamp = scratch_.stamp;
  auto& g_raw = scratch_.g;
  auto& parent_raw = scratch_.parent;
  auto& closed_raw = scratch_.closed;
  const auto touch = [&](size_t i) {
    if (stamp[i] != id) {
      stamp[i] = id;
      g_raw[i] = std::numeric_limits<float>::infinity();
      parent_raw[i] = -1;
      closed_raw[i] = 0;
    }
  };
  auto g = [&](size_t i) -> float& { touch(i); return g_raw[i]; };
  auto parent = [&](size_t i) -> int& { touch(i); return parent_raw[i]; };
  auto closed = [&](size_t i) -> uint8_t& { touch(i); return closed_raw[i]; };
  using Item = std::pair<float, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const int s = idx(start), t = idx(goal);
  g(static_cast<size_t>(s)) = 0;
  open.push({dist(start, goal), s});
  std::vector<Cell> border;
  const auto relax = [&](int u, const Cell& v, float step) {
    const int vi = idx(v);
    const float nv = g(static_cast<size_t>(u)) + step;
    if (nv < g(static_cast<size_t>(vi))) {
      g(static_cast<size_t>(vi)) = nv;
      parent(static_cast<size_t>(vi)) = u;
      open.push({nv + dist(v, goal), vi});
    }
  };
  int expanded = 0;
  while (!open.empty()) {
    const auto [f, u] = open.top();
    open.pop();
    if (closed(static_cast<size_t>(u))) continue;
    closed(static_cast<size_t>(u)) = 1;
    ++expanded;
    if (u == t) break;
    const Cell cu = cell(u);
    const int q = quad_at(cu);
    const Quad& quad = quads_[static_cast<size_t>(q)];
    const float cost = static_cast<float>(grid_.level_cost(quad.level));
    // Inside the quad: straight to the goal if it is here, and to every cell of its frame;
    // only for a cell that entered the quad from outside (or the start): one reached from
    // inside was relaxed past already by its parent, whose straight line is no longer (the quad
    // is convex and of one cost).
    const int from = parent(static_cast<size_t>(u));
    if (from < 0 || quad_of_cell_[static_cast<size_t>(from)] != q) {
      if (q == qg) relax(u, goal, dist(cu, goal) * cost);
      border_cells(q, &border);
      for (const Cell& v : border)
        if (!closed(static_cast<size_t>(idx(v)))) relax(u, v, dist(cu, v) * cost);
    }
    // Across the frame: the neighbouring cells of adjoining quads.
    const bool on_frame = cu.x() == quad.x0 || cu.y() == quad.y0 || cu.x() == quad.x0 + quad.size - 1 ||
                          cu.y() == quad.y0 + quad.size - 1;
    if (!on_frame) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const Cell v(cu.x() + dx, cu.y() + dy);
        const int qv = quad_at(v);
        if (qv < 0 || qv == q || closed(static_cast<size_t>(idx(v)))) continue;
        const float cv = static_cast<float>(grid_.level_cost(quads_[static_cast<size_t>(qv)].level));
        relax(u, v, dist(cu, v) * 0.5f * (cost + cv));
      }
    }
  }
  if (stats) stats->expanded = expanded;
  if (!closed(static_cast<size_t>(t))) return std::nullopt;
  std::vector<Cell> path;
  for (int i = t; i >= 0; i = parent(static_cast<size_t>(i))) path.push_back(cell(i));
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace rgnav::planner
