// The rendered_doors section of rgnav_rect_bench: door frames of a simulated building seen by
// the simulated head (drivers/sim stereo_renderer.h) from random places 2.4-5 m in front of
// them (either side, at most 50 degrees off the door's normal, the head tilted to the door's
// middle; views where a corner of the frame is hidden are drawn again), through the whole
// detector: dense stereo (vision/dense_stereo.h), LSD lines, quadrangles, rectangles
// (vision/rectangle_detector.h). A door is found when a detected rectangle's every corner lies
// within 10 cm of the door opening's (or the frame's outer outline's) in the world; height and
// width errors of the found ones against the opening.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace rgnav::bench {

nlohmann::json rendered_doors(const std::string& world_file, const std::string& calibration_file, int views,
                              uint64_t seed);

}  // namespace rgnav::bench
