#include "scan_conversions.h"

#include <algorithm>

#include "msg/conversions.h"

namespace rgnav::drivers::sick {

int64_t ScanIdSequence::next(int64_t acquisition_utime)
{
  last_ = std::max(last_ + 1, std::max<int64_t>(acquisition_utime, 1));
  return last_;
}

rgnav::laser_scan_t to_laser_scan_msg(const Lms2xxScan& scan, const std::string& sensor, int64_t scan_id)
{
  rgnav::laser_scan_t m = msg::to_msg(scan.scan);
  m.scan_id = scan_id;
  m.sensor = sensor;
  return m;
}

}  // namespace rgnav::drivers::sick
