// ALIGNED_SCAN / GATEWAY_EVENTS / OBJECTS_3D messages -> the kernel's plain inputs.
#pragma once

#include <string>
#include <vector>

#include "procs/rg_kernel/rg_kernel.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/gateway_event_t.hpp"
#include "rgnav/objects3d_t.hpp"

namespace rgnav::rg_kernel {

ScanInput to_input(const aligned_scan_t& m);
GatewayEventInput to_input(const gateway_event_t& m);
// The message's rectangles (base frame at capture) in the map frame of `map_from_base`; empty
// with *why set if one of them is no plausible rectangle (not finite, beyond 100 m, sides not in
// (0, 10] m): a malformed message is dropped whole.
std::vector<rgmap::Rectangle3d> to_rectangles(const objects3d_t& m, const geometry::Pose2& map_from_base, std::string* why);

}  // namespace rgnav::rg_kernel
