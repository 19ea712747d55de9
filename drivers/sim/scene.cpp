#include "sim/scene.h"

#include <algorithm>
#include <cmath>

#include "geometry/segment2.h"

namespace rgnav::sim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Liang-Barsky: does segment a-b touch the axis-aligned box [lo, hi]?
bool segment_touches_box(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi)
{
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int k = 0; k < 2; ++k) {
    if (std::fabs(d[k]) < 1e-15) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k];
    double tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

double ray_segment(const Vec2& o, const Vec2& d, const Vec2& a, const Vec2& b)
{
  // Parallel (below 1e-12): grazing a wall end-on is no return.
  const auto hit = geometry::ray_meets_line(o, d, a, b, 1e-12);
  if (!hit) return kInf;
  const double t = hit->along_ray, u = hit->along_line;
  if (t < 0.0 || u < 0.0 || u > 1.0) return kInf;
  return t;
}

double ray_circle(const Vec2& o, const Vec2& d, const Vec2& c, double r)
{
  const Vec2 oc = o - c;
  const double b = oc.dot(d);
  const double cc = oc.squaredNorm() - r * r;
  if (cc <= 0.0) return 0.0;
  const double disc = b * b - cc;
  if (disc < 0.0) return kInf;
  const double t = -b - std::sqrt(disc);
  return t >= 0.0 ? t : kInf;
}

Scene::Scene(const World& world, double cell_size) : cell_(cell_size)
{
  for (size_t i = 0; i < world.walls.size(); ++i) {
    const auto& w = world.walls[i];
    add_segment(w.a, w.b, w.z_min, w.z_max, -1, "wall[" + std::to_string(i) + "]");
  }
  for (size_t i = 0; i < world.doors.size(); ++i) {
    const auto& d = world.doors[i];
    add_segment(d.hinge, d.latch, 0.0, d.height, static_cast<int32_t>(i), "door " + d.name);
  }
  auto add_box = [this](const Box& box) {
    const auto c = box.corners();
    for (size_t k = 0; k < 4; ++k) add_segment(c[k], c[(k + 1) % 4], box.z_min, box.z_max, -1, box.name);
  };
  for (const auto& b : world.boxes) add_box(b);
  for (const auto& t : world.tables)
    for (const auto& part : t.parts()) add_box(part);
  build_grid();
}

void Scene::add_segment(const Vec2& a, const Vec2& b, double z_min, double z_max, int32_t door,
                        const std::string& owner)
{
  if (owner_names_.empty() || owner_names_.back() != owner) owner_names_.push_back(owner);
  segments_.push_back({a, b, static_cast<float>(z_min), static_cast<float>(z_max), door,
                       static_cast<int32_t>(owner_names_.size() - 1)});
}

void Scene::build_grid()
{
  Vec2 lo(0, 0), hi(1, 1);
  if (!segments_.empty()) {
    lo = hi = segments_.front().a;
    for (const auto& s : segments_) {
      lo = lo.cwiseMin(s.a).cwiseMin(s.b);
      hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    }
  }
  origin_ = lo - Vec2(cell_, cell_);
  nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_)) + 1);

  std::vector<std::vector<uint32_t>> cells(static_cast<size_t>(nx_) * static_cast<size_t>(ny_));
  const double eps = 1e-6;
  for (uint32_t i = 0; i < segments_.size(); ++i) {
    const auto& s = segments_[i];
    const Vec2 slo = s.a.cwiseMin(s.b), shi = s.a.cwiseMax(s.b);
    const int x0 = std::max(0, static_cast<int>(std::floor((slo.x() - origin_.x()) / cell_ - eps)));
    const int x1 = std::min(nx_ - 1, static_cast<int>(std::floor((shi.x() - origin_.x()) / cell_ + eps)));
    const int y0 = std::max(0, static_cast<int>(std::floor((slo.y() - origin_.y()) / cell_ - eps)));
    const int y1 = std::min(ny_ - 1, static_cast<int>(std::floor((shi.y() - origin_.y()) / cell_ + eps)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 clo = origin_ + Vec2(x * cell_ - eps, y * cell_ - eps);
        const Vec2 chi = origin_ + Vec2((x + 1) * cell_ + eps, (y + 1) * cell_ + eps);
        if (segment_touches_box(s.a, s.b, clo, chi)) cells[static_cast<size_t>(y) * nx_ + x].push_back(i);
      }
  }
  cell_start_.assign(cells.size() + 1, 0);
  for (size_t c = 0; c < cells.size(); ++c) cell_start_[c + 1] = cell_start_[c] + static_cast<uint32_t>(cells[c].size());
  cell_items_.clear();
  cell_items_.reserve(cell_start_.back());
  for (const auto& c : cells) cell_items_.insert(cell_items_.end(), c.begin(), c.end());
}

RayHit Scene::cast(const Vec2& o, const Vec2& d, double max_range, const HeightBand& band,
                   const std::vector<uint8_t>& door_open) const
{
  RayHit best;
  // Clip the ray to the grid box (slab method).
  const Vec2 lo = origin_, hi = max_corner();
  double t_enter = 0.0, t_exit = max_range;
  for (int k = 0; k < 2; ++k) {
    if (std::fabs(d[k]) < 1e-15) {
      if (o[k] < lo[k] || o[k] > hi[k]) return best;
      continue;
    }
    double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t_enter = std::max(t_enter, ta);
    t_exit = std::min(t_exit, tb);
  }
  if (t_enter > t_exit) return best;

  const Vec2 p = o + d * t_enter;
  int ix = std::clamp(static_cast<int>(std::floor((p.x() - lo.x()) / cell_)), 0, nx_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor((p.y() - lo.y()) / cell_)), 0, ny_ - 1);
  const int step_x = d.x() > 0 ? 1 : -1;
  const int step_y = d.y() > 0 ? 1 : -1;
  const double delta_x = std::fabs(d.x()) > 1e-15 ? cell_ / std::fabs(d.x()) : kInf;
  const double delta_y = std::fabs(d.y()) > 1e-15 ? cell_ / std::fabs(d.y()) : kInf;
  double next_x = std::fabs(d.x()) > 1e-15 ? (lo.x() + (ix + (step_x > 0)) * cell_ - o.x()) / d.x() : kInf;
  double next_y = std::fabs(d.y()) > 1e-15 ? (lo.y() + (iy + (step_y > 0)) * cell_ - o.y()) / d.y() : kInf;

  while (true) {
    const size_t c = static_cast<size_t>(iy) * nx_ + ix;
    for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const SceneSegment& s = segments_[cell_items_[k]];
      if (!active(s, band, door_open)) continue;
      const double t = ray_segment(o, d, s.a, s.b);
      if (t < best.range) {
        best.range = t;
        best.owner = s.owner;
      }
    }
    const double cell_exit = std::min(next_x, next_y);
    // A hit inside this cell cannot be beaten by anything in later cells.
    if (best.range <= cell_exit || cell_exit > t_exit) break;
    if (next_x < next_y) {
      ix += step_x;
      next_x += delta_x;
      if (ix < 0 || ix >= nx_) break;
    } else {
      iy += step_y;
      next_y += delta_y;
      if (iy < 0 || iy >= ny_) break;
    }
  }
  if (best.range > max_range) best = RayHit{};
  return best;
}

Clearance Scene::clearance(const Vec2& p, double search_radius, const HeightBand& band,
                           const std::vector<uint8_t>& door_open) const
{
  Clearance best;
  const int x0 = std::max(0, static_cast<int>(std::floor((p.x() - search_radius - origin_.x()) / cell_)));
  const int x1 = std::min(nx_ - 1, static_cast<int>(std::floor((p.x() + search_radius - origin_.x()) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((p.y() - search_radius - origin_.y()) / cell_)));
  const int y1 = std::min(ny_ - 1, static_cast<int>(std::floor((p.y() + search_radius - origin_.y()) / cell_)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const size_t c = static_cast<size_t>(y) * nx_ + x;
      for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const SceneSegment& s = segments_[cell_items_[k]];
        if (!active(s, band, door_open)) continue;
        const double dist = geometry::point_segment_distance(p, s.a, s.b);
        if (dist < best.distance) {
          best.distance = dist;
          best.owner = s.owner;
        }
      }
    }
  if (best.distance > search_radius) best = Clearance{};
  return best;
}

}  // namespace rgnav::sim
