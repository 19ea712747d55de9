// A scan's valid returns as the kernel takes them (ScanInput::laser_points): the live node gets
// them from ALIGNED_SCAN, the offline pipeline from the scan mapper's scans, by this one function.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "sensors/laser_scan.h"

namespace rgnav::rg_kernel {

// Valid returns only (range_min < r < range_max), in beam order, laser frame; angles and
// points in double.
std::vector<Eigen::Vector2d> laser_points(const sensors::LaserScan& scan);

}  // namespace rgnav::rg_kernel
