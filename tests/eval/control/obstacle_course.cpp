#include "obstacle_course.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace rgnav::bench {
namespace {

constexpr double kLength = 14.0, kWidth = 3.0;

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Obstacle outlines: walls and box edges as segments.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> outlines(const sim::World& w)
{
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> out;
  for (const auto& wall : w.walls) out.emplace_back(wall.a, wall.b);
  for (const auto& box : w.boxes) {
    const auto c = box.corners();
    for (size_t i = 0; i < c.size(); ++i) out.emplace_back(c[i], c[(i + 1) % c.size()]);
  }
  return out;
}

double distance_to(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segs, const Eigen::Vector2d& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : segs) best = std::min(best, segment_distance(p, a, b));
  return best;
}

bool inside_a_box(const sim::World& w, const Eigen::Vector2d& p)
{
  for (const auto& box : w.boxes)
    if (sim::point_in_polygon(p, box.corners())) return true;
  return false;
}

sim::Wall wall(double x0, double y0, double x1, double y1)
{
  sim::Wall w;
  w.a = {x0, y0};
  w.b = {x1, y1};
  return w;
}

}  // namespace

bool passable(const sim::World& world, const Eigen::Vector2d& from, const Eigen::Vector2d& to, double clearance,
              double cell)
{
  const auto segs = outlines(world);
  Eigen::Vector2d lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const auto& [a, b] : segs) {
    lo = lo.cwiseMin(a).cwiseMin(b);
    hi = hi.cwiseMax(a).cwiseMax(b);
  }
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)), h = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell));
  auto centre = [&](int x, int y) { return Eigen::Vector2d(lo.x() + (x + 0.5) * cell, lo.y() + (y + 0.5) * cell); };
  auto free = [&](int x, int y) {
    const Eigen::Vector2d c = centre(x, y);
    return !inside_a_box(world, c) && distance_to(segs, c) >= clearance + 0.71 * cell;
  };
  auto cell_of = [&](const Eigen::Vector2d& p) {
    return std::make_pair(std::clamp(static_cast<int>((p.x() - lo.x()) / cell), 0, w - 1),
                          std::clamp(static_cast<int>((p.y() - lo.y()) / cell), 0, h - 1));
  };
  const auto [sx, sy] = cell_of(from);
  const auto [gx, gy] = cell_of(to);
  if (!free(sx, sy) || !free(gx, gy)) return false;
  std::vector<char> seen(static_cast<size_t>(w * h), 0);
  std::deque<std::pair<int, int>> open{{sx, sy}};
  seen[static_cast<size_t>(sy * w + sx)] = 1;
  while (!open.empty()) {
    const auto [x, y] = open.front();
    open.pop_front();
    if (x == gx && y == gy) return true;
    const int dx[] = {1, -1, 0, 0}, dy[] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int nx = x + dx[k], ny = y + dy[k];
      if (nx < 0 || ny < 0 || nx >= w || ny >= h || seen[static_cast<size_t>(ny * w + nx)]) continue;
      seen[static_cast<size_t>(ny * w + nx)] = 1;
      if (free(nx, ny)) open.emplace_back(nx, ny);
    }
  }
  return false;
}

CourseDraw draw_course(std::mt19937& rng, double clearance, double personal_space)
{
  CourseDraw d;
  for (;; ++d.redrawn) {
    Course c;
    c.world.name = "course";
    c.world.walls = {wall(-1, -kWidth / 2, kLength, -kWidth / 2), wall(-1, kWidth / 2, kLength, kWidth / 2),
                     wall(-1, -kWidth / 2, -1, kWidth / 2), wall(kLength, -kWidth / 2, kLength, kWidth / 2)};
    std::uniform_real_distribution<double> ux(2.0, 10.5), uy(-0.8, 0.8), us(0.3, 0.7), uyaw(0, M_PI);
    std::uniform_int_distribution<int> nbox(2, 4), nppl(1, 2);
    const int nb = nbox(rng);
    for (int i = 0; i < nb; ++i) {
      sim::Box b;
      b.name = "box" + std::to_string(i);
      b.center = {ux(rng), uy(rng)};
      b.size = {us(rng), us(rng)};
      b.yaw = uyaw(rng);
      c.world.boxes.push_back(b);
    }
    std::uniform_real_distribution<double> px(3.0, 11.0), pv(0.4, 0.9), pd(0.0, 8.0);
    const int np = nppl(rng);
    bool consistent = true;
    const auto segs = outlines(c.world);
    for (int i = 0; i < np; ++i) {
      sim::Person p;
      p.name = "p" + std::to_string(i);
      const double x = px(rng);
      p.path = {{x, -1.2}, {x + 0.5, 1.2}};  // crossing the corridor back and forth
      p.loop = false;
      p.speed = pv(rng);
      p.start_delay = pd(rng);
      p.personal_space = personal_space;
      // People walk around furniture: the whole crossing keeps their radius from the boxes.
      for (double t = 0.0; t <= 1.0 + 1e-9; t += 0.02) {
        const Eigen::Vector2d q = p.path[0] + t * (p.path[1] - p.path[0]);
        if (inside_a_box(c.world, q) || distance_to(segs, q) < p.radius + 0.05)
          consistent = false;
      }
      c.world.people.push_back(p);
    }
    for (double x = 1.0; x <= 12.0 + 1e-9; x += 1.0) c.targets.emplace_back(x, 0.0, 0.0);
    if (consistent && passable(c.world, {0.0, 0.0}, {12.0, 0.0}, clearance)) {
      d.course = std::move(c);
      return d;
    }
  }
}

}  // namespace rgnav::bench
