#include "scan_mapper/input_checks.h"

#include <cmath>

namespace rgnav::scan_mapper {

std::string check_scan(const sensors::LaserScan& s, const InputLimits& l)
{
  if (s.scan_id <= 0) return "scan id must be > 0";
  if (s.utime < 0 || s.utime > l.max_utime) return "scan time outside [0, year 2100]";
  if (s.ranges.empty() || s.ranges.size() > l.max_beams) return "beam count outside [1, " + std::to_string(l.max_beams) + "]";
  if (!std::isfinite(s.angle_min) || std::fabs(s.angle_min) > 2.0 * M_PI + 1e-3) return "angle_min not within +-2 pi";
  if (!std::isfinite(s.angle_increment) || !(s.angle_increment > 0.f)) return "angle_increment must be > 0";
  // The beams' bearings must fit one turn: otherwise the count and the angles disagree.
  if (static_cast<double>(s.angle_increment) * static_cast<double>(s.ranges.size() - 1) > 2.0 * M_PI + 1e-3)
    return "beams span more than 360 deg (count and angle_increment disagree)";
  if (!std::isfinite(s.range_min) || !std::isfinite(s.range_max) || !(s.range_min >= 0.f) || !(s.range_max > s.range_min) ||
      s.range_max > l.max_range_m)
    return "need 0 <= range_min < range_max <= " + std::to_string(static_cast<int>(l.max_range_m)) + " m";
  for (float r : s.ranges)
    if (!std::isfinite(r) || r < 0.f) return "a range is negative or not finite";
  return "";
}

std::string check_odometry(const OdometrySample& o, const InputLimits& l)
{
  if (o.utime < 0 || o.utime > l.max_utime) return "odometry time outside [0, year 2100]";
  const auto& p = o.odom_from_base;
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.theta())) return "odometry pose not finite";
  if (std::fabs(p.x()) > l.max_coordinate_m || std::fabs(p.y()) > l.max_coordinate_m)
    return "odometry pose more than " + std::to_string(static_cast<int>(l.max_coordinate_m)) + " m from its origin";
  return "";
}

}  // namespace rgnav::scan_mapper
