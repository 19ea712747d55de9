// A small RG map made by hand, for localizer tests and the fault suite: two rooms joined by a
// door, each region with its line map and freespace bitmap, and the same walls for ray casting.
//   region 1 "room_a": map [0, 4] x [0, 3], its frame is the map frame; a cabinet in the
//                      top-left corner [0, 0.6] x [2.4, 3]
//   region 2 "room_b": map [4, 9] x [-1, 3], its frame at map (4, 0, 0)
//   gateway 1 (door):  map x = 4, y in [1.1, 1.9], region_a 1, region_b 2
// Neither room looks like itself turned or shifted, so a scan has one place in the map.
#pragma once

#include <cstdint>
#include <string>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"
#include "sensors/laser_scan.h"
#include "wall_world.h"

namespace rgnav::testing {

struct TwoRoomWorld
{
  rgmap::RgMap map;
  Walls walls;                     // map frame
  int64_t room_a = 0, room_b = 0, door = 0;
};

TwoRoomWorld two_room_world();

// The walls (region frame) as the region's line map, well supported.
void add_lines(rgmap::Region* r, const Walls& walls);

// An LMS 2xx-like scan (181 beams over 180 deg, 8 m) from map_from_base, the laser at
// base_from_laser; no return is range_max.
sensors::LaserScan cast_scan(const Walls& walls, const geometry::Pose2& map_from_base, const geometry::Pose2& base_from_laser,
                             int64_t utime, int64_t scan_id);

// Writes the map as <dir>/rgmap.json the way the RG kernel does (checkpoint framing).
void write_rgmap_json(const rgmap::RgMap& map, const std::string& dir);

}  // namespace rgnav::testing
