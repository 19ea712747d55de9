#include "twin_rooms.h"

#include <cmath>

#include "two_room_map.h"

namespace rgnav::testing {

using Eigen::Vector2d;
using geometry::Pose2;

namespace {

constexpr int64_t kTwinUtime = 1'700'000'000'000'000;

// A finalised region at map_from_region with these walls (region frame) and the freespace
// of the room [0, 4] x [0, 3] at 0.1 m, less what lies inside `blocked` rectangles.
// `mapped` (default: walls): the lines the map holds, when its scans missed some walls.
int64_t add_room(rgmap::RgMap* map, Walls* world, const Pose2& map_from_region, const Walls& walls,
                 const std::vector<std::pair<Vector2d, Vector2d>>& blocked, const Walls* mapped = nullptr)
{
  rgmap::Region& r = map->add_region(map_from_region, kTwinUtime);
  r.state = rgmap::Region::State::kFinalised;
  add_lines(&r, mapped ? *mapped : walls);
  for (const auto& w : walls) world->push_back({map_from_region * w.a, map_from_region * w.b});
  constexpr double res = 0.1;
  const int w = 42, h = 32;
  rgmap::FreespaceBitmap fs(res, Pose2(-res, -res, 0), w, h);
  for (int cy = 0; cy < h; ++cy)
    for (int cx = 0; cx < w; ++cx) {
      const Vector2d c(-res + (cx + 0.5) * res, -res + (cy + 0.5) * res);
      bool free = c.x() > 0 && c.x() < 4 && c.y() > 0 && c.y() < 3;
      for (const auto& [lo, hi] : blocked) free = free && !(c.x() > lo.x() && c.y() > lo.y() && c.x() < hi.x() && c.y() < hi.y());
      fs.set_free(cx, cy, free);
    }
  r.freespace = fs;
  r.bbox_min = Vector2d(0, 0);
  r.bbox_max = Vector2d(4, 3);
  r.nscans = 40;
  return r.id;
}

}  // namespace

TwinRoomWorld twin_room_world(bool corner_cut_in_b)
{
  using V = Vector2d;
  TwinRoomWorld t;
  // Outlines, not boxes against the walls: the likelihood field scores a beam end by its
  // distance to the nearest line, so a wall hidden behind a box still explains beams that pass
  // where the box would stand; a corner cut off the room changes where the walls are.
  const auto outline = [](const std::vector<V>& corners) {
    Walls walls;
    for (size_t k = 0; k < corners.size(); ++k) walls.push_back({corners[k], corners[(k + 1) % corners.size()]});
    return walls;
  };
  const std::pair<V, V> cabinet{V(0, 2.2), V(1, 3)}, notch{V(3, 0), V(4, 1)};
  t.room_a = add_room(&t.map, &t.walls, Pose2(), outline({V(0, 0), V(4, 0), V(4, 3), V(1, 3), V(1, 2.2), V(0, 2.2)}), {cabinet});
  if (corner_cut_in_b) {
    t.room_b = add_room(&t.map, &t.walls, Pose2(10, 0, 0),
                        outline({V(0, 0), V(3, 0), V(3, 1), V(4, 1), V(4, 3), V(1, 3), V(1, 2.2), V(0, 2.2)}), {cabinet, notch});
  } else {
    t.room_b = add_room(&t.map, &t.walls, Pose2(10, 0, 0), outline({V(0, 0), V(4, 0), V(4, 3), V(1, 3), V(1, 2.2), V(0, 2.2)}), {cabinet});
  }
  t.map.current_region = t.room_a;
  t.map.version = 1;
  t.map.utime = kTwinUtime;
  return t;
}

TwinRoomWorld twin_room_world_with_map_gap()
{
  using V = Vector2d;
  TwinRoomWorld t;
  const std::vector<V> corners{V(0, 0), V(4, 0), V(4, 3), V(1, 3), V(1, 2.2), V(0, 2.2)};
  Walls walls;
  for (size_t k = 0; k < corners.size(); ++k) walls.push_back({corners[k], corners[(k + 1) % corners.size()]});
  // Room_b's map lacks the cabinet's two faces (its scans never saw them: not carved free either).
  Walls mapped_b{{V(0, 0), V(4, 0)}, {V(4, 0), V(4, 3)}, {V(4, 3), V(1, 3)}, {V(0, 2.2), V(0, 0)}};
  const std::pair<V, V> cabinet{V(0, 2.2), V(1, 3)};
  t.room_a = add_room(&t.map, &t.walls, Pose2(), walls, {cabinet});
  t.room_b = add_room(&t.map, &t.walls, Pose2(10, 0, 0), walls, {cabinet}, &mapped_b);
  t.map.current_region = t.room_a;
  t.map.version = 1;
  t.map.utime = kTwinUtime;
  return t;
}

}  // namespace rgnav::testing
