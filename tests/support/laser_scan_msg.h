// A laser_scan_t with the front laser's geometry (181 beams over 180 degrees) and every beam at
// one range, for tests that need a scan but not what it sees (or fill the ranges themselves).
#pragma once

#include <cmath>
#include <cstdint>

#include "rgnav/laser_scan_t.hpp"

namespace rgnav::testing {

inline laser_scan_t laser_scan_msg(int64_t utime, int64_t scan_id, float range_max, float range)
{
  laser_scan_t s{};
  s.utime = utime;
  s.scan_id = scan_id;
  s.sensor = "laser_front";
  s.angle_min = static_cast<float>(-M_PI / 2);
  s.angle_increment = static_cast<float>(M_PI / 180);
  s.range_max = range_max;
  s.nranges = 181;
  s.ranges.assign(181, range);
  return s;
}

}  // namespace rgnav::testing
