// Lms2xxScan (driver library) → laser_scan_t (LCM), and the scan id rule.
#pragma once

#include <cstdint>
#include <string>

#include "lms2xx_driver.h"
#include "rgnav/laser_scan_t.hpp"

namespace rgnav::drivers::sick {

// scan_id must be unique and strictly increasing per sensor, also across driver restarts,
// with no state on disk: it is the scan's acquisition time in µs, bumped by one when two
// scans would share (or a stepped-back clock would reverse) it. A restart resumes above
// every id of the previous run as long as the wall clock did not jump back.
class ScanIdSequence
{
 public:
  int64_t next(int64_t acquisition_utime);

 private:
  int64_t last_ = 0;
};

// The device scan as sent: named and numbered by the node (common/msg/conversions.h does the rest).
rgnav::laser_scan_t to_laser_scan_msg(const Lms2xxScan& scan, const std::string& sensor, int64_t scan_id);

}  // namespace rgnav::drivers::sick
