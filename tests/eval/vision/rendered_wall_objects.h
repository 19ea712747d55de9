// The rendered_wall_objects section of rgnav_rect_bench: the whiteboards and posters of a
// simulated building (its wall_objects) seen by the simulated head from random places 1.2-4 m in
// front of them (at most 50 degrees off their normal, the head tilted to their middle; views
// where a corner is hidden are drawn again), through the whole detector as rendered_doors.h does
// it. An object is found when a detected rectangle's every corner lies within 10 cm of its
// corners; then the kind the vision gives it (vision/object_rectangles.h: whiteboards by the
// white inside them) is counted: whiteboards called whiteboards, posters called whiteboards.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace rgnav::bench {

nlohmann::json rendered_wall_objects(const std::string& world_file, const std::string& calibration_file, int views,
                                     uint64_t seed);

}  // namespace rgnav::bench
