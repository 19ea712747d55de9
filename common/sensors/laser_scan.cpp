#include "sensors/laser_scan.h"

#include <algorithm>

namespace rgnav::sensors {

size_t LaserScan::index_of(double b) const
{
  if (ranges.empty()) return 0;
  const double i = std::round((b - angle_min) / angle_increment);
  return static_cast<size_t>(std::clamp(i, 0.0, static_cast<double>(ranges.size() - 1)));
}

LaserScan with_message_precision(LaserScan scan)
{
  scan.angle_min = static_cast<float>(scan.angle_min);
  scan.angle_increment = static_cast<float>(scan.angle_increment);
  scan.range_min = static_cast<float>(scan.range_min);
  scan.range_max = static_cast<float>(scan.range_max);
  scan.scan_time = static_cast<float>(scan.scan_time);
  return scan;
}

}  // namespace rgnav::sensors
