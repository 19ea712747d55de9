// ALIGNED_SCAN / GATEWAY_EVENTS messages -> the kernel's plain inputs.
#pragma once

#include "procs/rg_kernel/rg_kernel.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/gateway_event_t.hpp"
#include "sensors/laser_scan.h"

namespace rgnav::rg_kernel {

// Valid returns only (range_min < r < range_max), in beam order, laser frame; angles and
// points in double.
std::vector<Eigen::Vector2d> laser_points(const sensors::LaserScan& scan);
ScanInput to_input(const aligned_scan_t& m);
GatewayEventInput to_input(const gateway_event_t& m);

}  // namespace rgnav::rg_kernel
