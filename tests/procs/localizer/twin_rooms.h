// Two rooms that look alike, made by hand, for the localizer's global localization tests: the
// same 4 x 3 m room twice, as two regions with no gateway between them, its top-left corner
// [0, 1] x [2.2, 3] cut off (so neither room looks like itself turned). Region frames sit at
// the rooms' bottom-left corners, so a pose means the same spot in either room.
//   region room_a: map [0, 4] x [0, 3]
//   region room_b: map [10, 14] x [0, 3]; with `corner_cut_in_b` also its bottom-right corner
//                  cut off, region frame [3, 4] x [0, 1]: the one thing that tells them apart
#pragma once

#include <cstdint>

#include "rgmap/rg_map.h"
#include "wall_world.h"

namespace rgnav::testing {

struct TwinRoomWorld
{
  rgmap::RgMap map;
  Walls walls;   // map frame
  int64_t room_a = 0, room_b = 0;
};

TwinRoomWorld twin_room_world(bool corner_cut_in_b);
// The same room twice, alike in the world; but room_b's map lacks the cabinet's two faces (the
// mapping scans never saw them, so its freespace is not carved there either): a gap in one map
// that the other fills.
TwinRoomWorld twin_room_world_with_map_gap();

}  // namespace rgnav::testing
