// A simulator step's odometry samples and scans in time order, as a bus would deliver them:
// before each scan the odometry samples up to its time, the step's later samples last. Whatever
// feeds a mapper from the simulator (the mapping evaluations, the offline pipeline's test) needs
// this order: a scan is placed by the odometry before it.
#pragma once

#include <cstddef>

#include "sim/simulator.h"

namespace rgnav::sim {

// Calls on_odometry(const OdometrySample&) and on_scan(const sensors::LaserScan&) in that order.
template <class OnOdometry, class OnScan>
void in_time_order(const StepOutput& out, OnOdometry&& on_odometry, OnScan&& on_scan)
{
  size_t oi = 0;
  for (const auto& s : out.scans) {
    for (; oi < out.odometry.size() && out.odometry[oi].utime <= s.utime; ++oi) on_odometry(out.odometry[oi]);
    on_scan(s);
  }
  for (; oi < out.odometry.size(); ++oi) on_odometry(out.odometry[oi]);
}

}  // namespace rgnav::sim
