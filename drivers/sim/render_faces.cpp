#include "sim/render_faces.h"

#include <algorithm>
#include <cmath>

namespace rgnav::sim {

namespace {

// Surface ids: static surfaces count up from 1; door leaves and people have fixed ranges so a
// door or person looks the same in every frame whatever else is in it.
constexpr uint32_t kDoorSurfaces = 1u << 28;
constexpr uint32_t kPersonSurfaces = 2u << 28;

constexpr double kFrameWidth = 0.06;   // [m] door jambs and lintel, along the wall and up
constexpr double kFrameDepth = 0.2;    // [m] across the wall
constexpr double kLeafThickness = 0.04;
constexpr double kOpenLeafOffset = 0.1;  // [m] an open leaf stands this far off the wall line
constexpr int kPersonSides = 12;

Eigen::Vector3d at(const Vec2& p, double z) { return {p.x(), p.y(), z}; }

// A vertical rectangle over the segment a-b from z0 to z1.
Face vertical(const Vec2& a, const Vec2& b, double z0, double z1, Material m, uint32_t surface, double s_offset = 0)
{
  Face f;
  const Vec2 d = b - a;
  f.origin = at(a, z0);
  f.u = Eigen::Vector3d(d.x(), d.y(), 0).normalized();
  f.v = Eigen::Vector3d::UnitZ();
  f.width = d.norm();
  f.height = z1 - z0;
  f.material = m;
  f.surface = surface;
  f.s_offset = s_offset;
  return f;
}

// A horizontal rectangle at height z spanned by the corner c0 and the edges e1, e2 (orthogonal).
Face horizontal(const Vec2& c0, const Vec2& e1, const Vec2& e2, double z, Material m, uint32_t surface)
{
  Face f;
  f.origin = at(c0, z);
  f.u = Eigen::Vector3d(e1.x(), e1.y(), 0).normalized();
  f.v = Eigen::Vector3d(e2.x(), e2.y(), 0).normalized();
  f.width = e1.norm();
  f.height = e2.norm();
  f.material = m;
  f.surface = surface;
  return f;
}

// Corners (CCW) of a rectangle centred at c with extents along direction `along` and across it.
std::vector<Vec2> oriented_rect(const Vec2& c, const Vec2& along, double length, double depth)
{
  const Vec2 u = along.normalized() * (length / 2);
  const Vec2 n = Vec2(-along.y(), along.x()).normalized() * (depth / 2);
  return {c - u - n, c + u - n, c + u + n, c - u + n};
}

}  // namespace

double ceiling_height(const World& world)
{
  double top = 0;
  for (const auto& w : world.walls) top = std::max(top, w.z_max);
  return top > 0 ? top : 2.5;
}

void append_box(const std::vector<Vec2>& corners, double z_min, double z_max, Material m, uint32_t surface,
                std::vector<Face>* out)
{
  double s = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec2& a = corners[i];
    const Vec2& b = corners[(i + 1) % corners.size()];
    out->push_back(vertical(a, b, z_min, z_max, m, surface, s));
    s += (b - a).norm();
  }
  if (corners.size() == 4) {
    out->push_back(horizontal(corners[0], corners[1] - corners[0], corners[3] - corners[0], z_max, m, surface));
    out->push_back(horizontal(corners[0], corners[1] - corners[0], corners[3] - corners[0], z_min, m, surface));
  }
}

std::vector<Face> static_faces(const World& world)
{
  std::vector<Face> out;
  uint32_t next = 1;
  const double ceiling = ceiling_height(world);
  Vec2 lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const auto& w : world.walls) {
    out.push_back(vertical(w.a, w.b, w.z_min, w.z_max, Material::kWall, next++));
    lo = lo.cwiseMin(w.a).cwiseMin(w.b);
    hi = hi.cwiseMax(w.a).cwiseMax(w.b);
  }
  for (const auto& d : world.doors) {
    const Vec2 along = (d.latch - d.hinge).normalized();
    const double top = d.height + kFrameWidth;
    // The wall above the opening (worlds leave the whole gap open), then jambs and lintel.
    if (ceiling > top) out.push_back(vertical(d.hinge, d.latch, top, ceiling, Material::kWall, next++));
    const uint32_t frame = next++;
    append_box(oriented_rect(d.hinge - along * (kFrameWidth / 2), along, kFrameWidth, kFrameDepth), 0, top,
               Material::kDoorFrame, frame, &out);
    append_box(oriented_rect(d.latch + along * (kFrameWidth / 2), along, kFrameWidth, kFrameDepth), 0, top,
               Material::kDoorFrame, frame, &out);
    append_box(oriented_rect((d.hinge + d.latch) / 2, along, d.width(), kFrameDepth), d.height, top,
               Material::kDoorFrame, frame, &out);
  }
  for (const auto& b : world.boxes) append_box(b.corners(), b.z_min, b.z_max, Material::kBox, next++, &out);
  for (const auto& t : world.tables) {
    const auto parts = t.parts();
    for (size_t i = 0; i < parts.size(); ++i) {
      const bool top = i + 1 == parts.size();
      append_box(parts[i].corners(), parts[i].z_min, parts[i].z_max, top ? Material::kTableTop : Material::kTableLeg,
                 next++, &out);
    }
  }
  for (const auto& o : world.wall_objects)
    out.push_back(vertical(o.a, o.b, o.z_min, o.z_max,
                           o.kind == WallObject::Kind::kWhiteboard ? Material::kWhiteboard : Material::kPoster, next++));
  if (world.walls.empty()) lo = hi = Vec2(0, 0);
  lo -= Vec2(20, 20);
  hi += Vec2(20, 20);
  const Vec2 size = hi - lo;
  out.push_back(horizontal(lo, Vec2(size.x(), 0), Vec2(0, size.y()), 0.0, Material::kFloor, next++));
  out.push_back(horizontal(lo, Vec2(size.x(), 0), Vec2(0, size.y()), ceiling, Material::kCeiling, next++));
  return out;
}

void append_dynamic_faces(const World& world, const std::vector<uint8_t>& door_open,
                          const std::vector<Circle>& people, std::vector<Face>* out)
{
  for (size_t i = 0; i < world.doors.size(); ++i) {
    const Door& d = world.doors[i];
    const Vec2 along = (d.latch - d.hinge).normalized();
    const Vec2 normal(-along.y(), along.x());
    const bool open = i < door_open.size() && door_open[i] != 0;
    // Closed: across the opening. Open: turned flat beside the wall (the simulator's laser and
    // body treat an open door as gone, so the cameras must not see it block anything).
    const Vec2 centre = open ? Vec2(d.hinge - along * (d.width() / 2) + normal * kOpenLeafOffset)
                             : Vec2((d.hinge + d.latch) / 2);
    append_box(oriented_rect(centre, along, d.width(), kLeafThickness), 0, d.height, Material::kDoorLeaf,
               kDoorSurfaces + static_cast<uint32_t>(i), out);
  }
  const size_t n = std::min(people.size(), world.people.size());
  for (size_t j = 0; j < n; ++j) {
    const Circle& c = people[j];
    std::vector<Vec2> ring;
    for (int k = 0; k < kPersonSides; ++k) {
      const double a = 2 * M_PI * k / kPersonSides;
      ring.push_back(c.center + c.radius * Vec2(std::cos(a), std::sin(a)));
    }
    double s = 0;
    for (int k = 0; k < kPersonSides; ++k) {
      const Vec2& a = ring[static_cast<size_t>(k)];
      const Vec2& b = ring[static_cast<size_t>((k + 1) % kPersonSides)];
      out->push_back(vertical(a, b, 0, world.people[j].height, Material::kPerson,
                              kPersonSurfaces + static_cast<uint32_t>(j), s));
      s += (b - a).norm();
    }
  }
}

}  // namespace rgnav::sim
