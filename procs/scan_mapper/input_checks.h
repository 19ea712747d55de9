// What the scan mapper refuses at its boundary. The bus already rejects undecodable messages
// and non-finite numbers; these checks catch what decodes but would still poison the map or
// its persisted state (absurd geometry, poses kilometres away, time going back), so that a
// hostile or broken sender costs one dropped message, never the process or the checkpoint.
// Each returns "" when the input is usable, else why not.
#pragma once

#include <cstdint>
#include <string>

#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

struct InputLimits
{
  double max_range_m = 1000.0;            // range_max above this is no laser of this robot
  size_t max_beams = 10000;
  double max_coordinate_m = 100'000.0;    // odometry farther from its origin is a broken driver
  int64_t max_utime = 4'102'444'800'000'000;  // 2100-01-01: later is a broken clock
  // Odometry more than this ahead of the previous sample is held until the next sample
  // confirms the new time (one absurd timestamp must not lock out all later odometry).
  int64_t max_odometry_gap_us = 10'000'000;
};

std::string check_scan(const sensors::LaserScan& scan, const InputLimits& limits = {});
std::string check_odometry(const OdometrySample& sample, const InputLimits& limits = {});

}  // namespace rgnav::scan_mapper
