#include "two_room_map.h"

#include <cmath>

#include "rgmap/saved_map.h"
#include "rgmap/rgmap_json.h"

namespace rgnav::testing {

using Eigen::Vector2d;
using geometry::Pose2;

void add_lines(rgmap::Region* r, const Walls& walls)
{
  for (const auto& w : walls) {
    rgmap::LineSegment s;
    s.a = w.a;
    s.b = w.b;
    s.sigma = 0.01;
    s.support = 50;
    r->segments.push_back(s);
  }
}

namespace {

constexpr int64_t kUtime = 1'700'000'000'000'000;

// Freespace at 0.1 m over [x0, x1] x [y0, y1] (region frame), less what `blocked` says.
template <class Blocked>
rgmap::FreespaceBitmap freespace(double x0, double y0, double x1, double y1, Blocked blocked)
{
  constexpr double res = 0.1;
  const int w = static_cast<int>(std::lround((x1 - x0) / res)) + 2, h = static_cast<int>(std::lround((y1 - y0) / res)) + 2;
  rgmap::FreespaceBitmap fs(res, Pose2(x0 - res, y0 - res, 0), w, h);
  for (int cy = 0; cy < h; ++cy)
    for (int cx = 0; cx < w; ++cx) {
      const Vector2d c(x0 - res + (cx + 0.5) * res, y0 - res + (cy + 0.5) * res);
      fs.set_free(cx, cy, c.x() > x0 && c.x() < x1 && c.y() > y0 && c.y() < y1 && !blocked(c));
    }
  return fs;
}

}  // namespace

TwoRoomWorld two_room_world()
{
  using V = Vector2d;
  TwoRoomWorld w;
  // Room A in its frame (= map frame): the door gap in its right wall, the cabinet.
  const Walls room_a = {{V(0, 0), V(4, 0)}, {V(4, 0), V(4, 1.1)}, {V(4, 1.9), V(4, 3)}, {V(4, 3), V(0, 3)},
                        {V(0, 3), V(0, 0)}, {V(0, 2.4), V(0.6, 2.4)}, {V(0.6, 2.4), V(0.6, 3)}};
  // Room B in its frame (origin at map (4, 0)): the door gap in its left wall.
  const Walls room_b = {{V(0, -1), V(5, -1)}, {V(5, -1), V(5, 3)}, {V(5, 3), V(0, 3)}, {V(0, 3), V(0, 1.9)},
                        {V(0, 1.1), V(0, -1)}};
  const Pose2 map_from_b(4, 0, 0);
  add(&w.walls, room_a);
  for (const auto& s : room_b) w.walls.push_back({map_from_b * s.a, map_from_b * s.b});

  rgmap::Region& a = w.map.add_region(Pose2(), kUtime);
  a.name = "room_a";
  a.state = rgmap::Region::State::kFinalised;
  add_lines(&a, room_a);
  a.freespace = freespace(0, 0, 4, 3, [](const V& c) { return c.x() < 0.6 && c.y() > 2.4; });
  a.bbox_min = V(0, 0);
  a.bbox_max = V(4, 3);
  a.nscans = 40;
  w.room_a = a.id;
  rgmap::Region& b = w.map.add_region(map_from_b, kUtime);
  b.name = "room_b";
  b.state = rgmap::Region::State::kFinalised;
  add_lines(&b, room_b);
  b.freespace = freespace(0, -1, 5, 3, [](const V&) { return false; });
  b.bbox_min = V(0, -1);
  b.bbox_max = V(5, 3);
  b.nscans = 40;
  w.room_b = b.id;

  rgmap::Gateway& g = w.map.add_gateway(rgmap::GatewayClass::kDoor, w.room_a, kUtime);
  g.gateway_points = {V(4, 1.1), V(4, 1.9)};
  g.crossing_points = {V(4, 1.5)};
  g.traversal_directions = {0.0};
  g.traversals = 1;
  w.door = g.id;
  w.map.connect(g.id, w.room_b, map_from_b);
  w.map.current_region = w.room_a;
  w.map.version = 1;
  w.map.utime = kUtime;
  return w;
}

sensors::LaserScan cast_scan(const Walls& walls, const Pose2& map_from_base, const Pose2& base_from_laser, int64_t utime,
                             int64_t scan_id)
{
  sensors::LaserScan s;
  s.utime = utime;
  s.scan_id = scan_id;
  s.sensor = "laser_front";
  s.angle_min = -M_PI / 2;
  s.angle_increment = M_PI / 180;
  s.range_min = 0.02;
  s.range_max = 8.0;
  s.scan_time = 1.0 / 75;
  const Pose2 map_from_laser = map_from_base * base_from_laser;
  for (int i = 0; i < 181; ++i) {
    const double a = map_from_laser.theta() + s.angle_min + i * s.angle_increment;
    const double r = nearest_wall(walls, map_from_laser.translation(), Vector2d(std::cos(a), std::sin(a)));
    s.ranges.push_back(static_cast<float>(std::min(r, s.range_max)));
  }
  return sensors::with_message_precision(s);
}

void write_rgmap_json(const rgmap::RgMap& map, const std::string& dir)
{
  rgmap::save_map(map, dir + "/rgmap.json");
}

}  // namespace rgnav::testing
