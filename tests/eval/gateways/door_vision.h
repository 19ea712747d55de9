// The camera of the door evaluation (sim_runs.h DoorVision): the simulated stereo head
// (drivers/sim stereo_renderer.h) at the robot's true pose, dense stereo and the rectangle
// detector of the vision (procs/vision), its rectangles in the base frame as the gateway
// detector takes them from OBJECTS_3D.
#pragma once

#include <memory>
#include <string>

#include "sim_runs.h"

namespace rgnav::gateway_detector::tools {

// Throws std::runtime_error if the calibration file does not load.
DoorVision make_door_vision(const sim::World& world, const std::string& calibration_file, double rate_hz, uint64_t seed);

}  // namespace rgnav::gateway_detector::tools
