// One planar laser scan as plain numbers: the fields of laser_scan_t (common/msg/conversions.h
// converts to and from it) and read-only helpers for its beams. Every process, driver, importer
// and tool uses this one type; a driver's extras (the SICK driver's receive time and status
// byte) live in a small struct of that driver that holds a LaserScan.
//
// Beams are counter-clockwise from angle_min in the laser frame (x forward, y left); every beam
// is a ray from the origin. A range is invalid when it is 0 or below range_min and means "no
// return" at or above range_max.
//
// The header is double, the ranges float. The message carries floats, so a scan that came over
// the bus holds float values in its double fields; the simulator's scans hold their exact
// double angles and range limits until they are sent (offline paths that skip the bus and want
// the bus's numbers use with_message_precision). All helpers compute in double.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace rgnav::sensors {

struct LaserScan
{
  int64_t utime = 0;             // [us] acquisition time of the first beam
  int64_t scan_id = 0;           // unique, strictly increasing per sensor; 0 until assigned
  std::string sensor;            // sensor name from the robot description, e.g. "laser_front"
  double angle_min = 0.0;        // [rad] bearing of beam 0
  double angle_increment = 0.0;  // [rad] bearing step between consecutive beams
  double range_min = 0.0;        // [m] readings below are invalid
  double range_max = 0.0;        // [m] readings at or above mean "no return"
  double scan_time = 0.0;        // [s] time for one full scan (0 if unknown)
  std::vector<float> ranges;     // [m] per beam

  size_t size() const { return ranges.size(); }
  double bearing(size_t i) const { return angle_min + angle_increment * static_cast<double>(i); }
  Eigen::Vector2d direction(size_t i) const
  {
    const double a = bearing(i);
    return {std::cos(a), std::sin(a)};
  }
  bool hit(size_t i) const { return ranges[i] >= range_min && ranges[i] > 0.0 && ranges[i] < range_max; }
  bool no_return(size_t i) const { return ranges[i] >= range_max; }
  bool invalid(size_t i) const { return !hit(i) && !no_return(i); }
  // The beam's end point in the laser frame.
  Eigen::Vector2d point(size_t i) const { return static_cast<double>(ranges[i]) * direction(i); }
  // Index of the beam nearest to `bearing` (clamped to the field of view); 0 for an empty scan.
  size_t index_of(double bearing) const;
};

// `scan` with angle_min, angle_increment, range_min, range_max and scan_time rounded to float as
// laser_scan_t carries them: the numbers a process sees once the scan went over the bus.
LaserScan with_message_precision(LaserScan scan);

}  // namespace rgnav::sensors
