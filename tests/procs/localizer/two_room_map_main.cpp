// two_room_map DIR: writes the hand-made two-room RG map (two_room_map.h) as DIR/rgmap.json,
// a saved map for the fault suite's localizer (tests/fault/sim_stack_configs.sh).
#include <iostream>

#include "two_room_map.h"

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::cerr << "usage: two_room_map DIR\n";
    return 2;
  }
  try {
    rgnav::testing::write_rgmap_json(rgnav::testing::two_room_world().map, argv[1]);
  } catch (const std::exception& e) {
    std::cerr << "two_room_map: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
