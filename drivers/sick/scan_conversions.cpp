#include "scan_conversions.h"

#include <algorithm>

namespace rgnav::drivers::sick {

int64_t ScanIdSequence::next(int64_t acquisition_utime)
{
  last_ = std::max(last_ + 1, std::max<int64_t>(acquisition_utime, 1));
  return last_;
}

rgnav::laser_scan_t to_laser_scan_msg(const LaserScan& scan, const std::string& sensor, int64_t scan_id)
{
  rgnav::laser_scan_t m;
  m.utime = scan.first_beam_utime;
  m.scan_id = scan_id;
  m.sensor = sensor;
  m.angle_min = static_cast<float>(scan.angle_min_rad);
  m.angle_increment = static_cast<float>(scan.angle_increment_rad);
  m.range_min = static_cast<float>(scan.range_min_m);
  m.range_max = static_cast<float>(scan.range_max_m);
  m.scan_time = static_cast<float>(scan.scan_time_s);
  m.nranges = static_cast<int32_t>(scan.ranges_m.size());
  m.ranges = scan.ranges_m;
  m.nintensities = 0;
  return m;
}

}  // namespace rgnav::drivers::sick
