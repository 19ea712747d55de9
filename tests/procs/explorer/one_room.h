// A hand-made one-room RG map for the explorer's node tests: region 1 (frame = map frame) is a
// 4 m x 3 m room, [0, 4] x [0, 3], its freespace all free at 0.1 m; walls on the west, south
// and north sides, and on the east side too when `closed` (else the east side is a frontier); a
// 1 m door in the north wall, x in [1.5, 2.5], when `north_door`.
#pragma once

#include "rgmap/rg_map.h"

namespace rgnav::explorer::test_maps {

inline rgmap::RgMap one_room(bool closed, int64_t version = 1, bool north_door = false)
{
  rgmap::RgMap map;
  rgmap::Region& r = map.add_region(geometry::Pose2(), 1'700'000'000'000'000);
  const auto wall = [&](double ax, double ay, double bx, double by) {
    rgmap::LineSegment s;
    s.a = {ax, ay};
    s.b = {bx, by};
    s.sigma = 0.01;
    s.support = 50;
    r.segments.push_back(s);
  };
  wall(0, 0, 4, 0);
  if (north_door) {
    wall(0, 3, 1.5, 3);
    wall(2.5, 3, 4, 3);
  } else {
    wall(0, 3, 4, 3);
  }
  wall(0, 0, 0, 3);
  if (closed) wall(4, 0, 4, 3);
  r.freespace = rgmap::FreespaceBitmap(0.1, geometry::Pose2(), 40, 30);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) r.freespace.set_free(x, y, true);
  r.bbox_min = {0, 0};
  r.bbox_max = {4, 3};
  r.nscans = 10;
  map.current_region = r.id;
  map.version = version;
  map.last_scan_id = 10;
  map.utime = 1'700'000'000'000'000;
  return map;
}

}  // namespace rgnav::explorer::test_maps
