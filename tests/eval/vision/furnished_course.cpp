#include "furnished_course.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::bench {

namespace {

using Vec2 = Eigen::Vector2d;

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

bool segments_cross(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b)
{
  const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p), d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

// Distance between two convex polygons (0 when they overlap).
double polygon_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b)
{
  if (sim::point_in_polygon(a[0], b) || sim::point_in_polygon(b[0], a)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) {
      const Vec2 &a0 = a[i], &a1 = a[(i + 1) % a.size()], &b0 = b[j], &b1 = b[(j + 1) % b.size()];
      if (segments_cross(a0, a1, b0, b1)) return 0.0;
      best = std::min({best, segment_distance(a0, b0, b1), segment_distance(a1, b0, b1), segment_distance(b0, a0, a1),
                       segment_distance(b1, a0, a1)});
    }
  return best;
}

double point_to_box(const Vec2& p, const sim::Box& b)
{
  const auto c = b.corners();
  if (sim::point_in_polygon(p, c)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < c.size(); ++i) best = std::min(best, segment_distance(p, c[i], c[(i + 1) % c.size()]));
  return best;
}

sim::Box box(const std::string& name, const Vec2& center, const Vec2& size, double yaw, double z_min, double z_max)
{
  sim::Box b;
  b.name = name;
  b.center = center;
  b.size = size;
  b.yaw = yaw;
  b.z_min = z_min;
  b.z_max = z_max;
  return b;
}

sim::Wall wall(const Vec2& a, const Vec2& b)
{
  sim::Wall w;
  w.a = a;
  w.b = b;
  return w;
}

bool fits(const sim::Box& candidate, const std::vector<sim::Box>& placed, double margin)
{
  const auto c = candidate.corners();
  for (const auto& p : placed)
    if (polygon_distance(c, p.corners()) < margin) return false;
  return true;
}

}  // namespace

std::vector<sim::Box> pedestal_chair(const std::string& name, const Vec2& center, double yaw)
{
  const Vec2 back = sim::rotate(Vec2(-0.2, 0.0), yaw);
  return {box(name + ".column", center, {0.06, 0.06}, yaw, 0.0, 0.44),
          box(name + ".seat", center, {0.45, 0.45}, yaw, 0.44, 0.50),
          box(name + ".back", center + back, {0.05, 0.45}, yaw, 0.50, 0.90)};
}

FurnishedCourse draw_furnished_course(std::mt19937& rng, const FurnishedCourseOptions& o)
{
  using U = std::uniform_real_distribution<double>;
  using I = std::uniform_int_distribution<int>;
  FurnishedCourse out;
  for (;; ++out.redrawn) {
    FurnishedCourse d;
    const double length = U(9.0, 11.0)(rng), half_width = 0.5 * U(4.4, 5.6)(rng);
    sim::World& w = d.course.world;
    w.name = "furnished_course";
    w.texture_seed = rng();
    w.walls = {wall({-1.0, -half_width}, {length, -half_width}), wall({length, -half_width}, {length, half_width}),
               wall({length, half_width}, {-1.0, half_width}), wall({-1.0, half_width}, {-1.0, -half_width})};
    const Vec2 start(0.0, 0.0), goal(length - 1.5, U(-0.8, 0.8)(rng));
    // Nothing within reach of the start and the goal: the robot starts and ends free.
    const double keep_free = o.clearance + 0.3;
    auto clear_of_ends = [&](const sim::Box& b) { return point_to_box(start, b) > keep_free && point_to_box(goal, b) > keep_free; };
    const int want_tables = I(2, 3)(rng), want_chairs = I(1, 3)(rng), want_shelves = I(0, 2)(rng);
    for (int i = 0, tries = 0; d.tables < want_tables && tries < 50; ++tries) {
      sim::Table t;
      t.name = "table" + std::to_string(i);
      t.center = {U(1.8, length - 3.0)(rng), U(-0.9, 0.9)(rng)};
      t.size = {U(1.2, 1.8)(rng), U(0.7, 1.0)(rng)};
      t.yaw = U(0.0, M_PI)(rng);
      t.height = U(0.72, 0.78)(rng);
      const sim::Box fp = box(t.name, t.center, t.size, t.yaw, 0.0, t.height);
      if (!clear_of_ends(fp) || !fits(fp, d.footprints, 0.6)) continue;
      w.tables.push_back(t);
      d.footprints.push_back(fp);
      ++d.tables;
      ++i;
    }
    for (int i = 0, tries = 0; d.chairs < want_chairs && tries < 50; ++tries) {
      Vec2 center;
      double yaw;
      if (!w.tables.empty() && I(0, 2)(rng) > 0) {
        // Pulled out from a table side, facing it.
        const sim::Table& t = w.tables[static_cast<size_t>(I(0, static_cast<int>(w.tables.size()) - 1)(rng))];
        const int side = I(0, 3)(rng);
        const double a = t.yaw + side * M_PI / 2;
        const double half = 0.5 * ((side % 2 == 0) ? t.size.x() : t.size.y());
        center = t.center + sim::rotate(Vec2(half + U(0.3, 0.45)(rng), U(-0.3, 0.3)(rng)), a);
        yaw = a + M_PI;
      } else {
        center = {U(1.5, length - 2.5)(rng), U(-1.2, 1.2)(rng)};
        yaw = U(-M_PI, M_PI)(rng);
      }
      const std::string name = "chair" + std::to_string(i);
      const sim::Box fp = box(name, center, {0.45, 0.45}, yaw, 0.0, 0.90);
      if (!clear_of_ends(fp) || !fits(fp, d.footprints, 0.05)) continue;
      for (const auto& part : pedestal_chair(name, center, yaw)) w.boxes.push_back(part);
      d.footprints.push_back(fp);
      ++d.chairs;
      ++i;
    }
    for (int i = 0, tries = 0; d.shelves < want_shelves && tries < 50; ++tries) {
      const double side = I(0, 1)(rng) ? 1.0 : -1.0, depth = U(0.35, 0.55)(rng), len = U(1.0, 2.0)(rng);
      const Vec2 center(U(1.5, length - 2.5)(rng), side * (half_width - 0.5 * depth));
      const sim::Box shelf = box("shelf" + std::to_string(i), center, {len, depth}, 0.0, U(0.5, 0.6)(rng), U(0.9, 1.0)(rng));
      if (!clear_of_ends(shelf) || !fits(shelf, d.footprints, 0.05)) continue;
      w.boxes.push_back(shelf);
      d.footprints.push_back(shelf);
      ++d.shelves;
      ++i;
    }
    // Passable in 3D: the footprints as full-height boxes among the walls.
    sim::World solid;
    solid.walls = w.walls;
    solid.boxes = d.footprints;
    if (!passable(solid, start, goal, o.clearance)) continue;
    const Vec2 way = goal - start;
    const double heading = std::atan2(way.y(), way.x());
    const int n = std::max(1, static_cast<int>(std::floor(way.norm() / o.target_spacing)));
    for (int k = 1; k < n; ++k) {
      const Vec2 p = start + way * (static_cast<double>(k) / n);
      bool free = true;
      for (const auto& fp : d.footprints) free = free && point_to_box(p, fp) > o.clearance + 0.1;
      if (free) d.course.targets.emplace_back(p.x(), p.y(), heading);
    }
    d.course.targets.emplace_back(goal.x(), goal.y(), heading);
    d.redrawn = out.redrawn;
    return d;
  }
}

}  // namespace rgnav::bench
