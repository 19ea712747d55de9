#include "msg/conversions.h"

namespace rgnav::msg {

sensors::LaserScan to_laser_scan(const laser_scan_t& m)
{
  sensors::LaserScan s;
  s.utime = m.utime;
  s.scan_id = m.scan_id;
  s.sensor = m.sensor;
  s.angle_min = m.angle_min;
  s.angle_increment = m.angle_increment;
  s.range_min = m.range_min;
  s.range_max = m.range_max;
  s.scan_time = m.scan_time;
  s.ranges = m.ranges;
  return s;
}

laser_scan_t to_msg(const sensors::LaserScan& s)
{
  laser_scan_t m;
  m.utime = s.utime;
  m.scan_id = s.scan_id;
  m.sensor = s.sensor;
  m.angle_min = static_cast<float>(s.angle_min);
  m.angle_increment = static_cast<float>(s.angle_increment);
  m.range_min = static_cast<float>(s.range_min);
  m.range_max = static_cast<float>(s.range_max);
  m.scan_time = static_cast<float>(s.scan_time);
  m.nranges = static_cast<int32_t>(s.ranges.size());
  m.ranges = s.ranges;
  m.nintensities = 0;
  return m;
}

}  // namespace rgnav::msg
