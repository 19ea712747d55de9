// Conversions between LCM message fields and the plain C++ types algorithms use (the
// `ToRigid3d(msg)` idea of cartographer_ros's msg_conversion.h). Only node adapters use these.
#pragma once

#include <Eigen/Core>

#include "geometry/pose2.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/point2d_t.hpp"
#include "rgnav/pose2d_t.hpp"
#include "sensors/laser_scan.h"

namespace rgnav::msg {

inline geometry::Pose2 to_pose2(const pose2d_t& m) { return geometry::Pose2(m.x, m.y, m.theta); }

inline pose2d_t to_msg(const geometry::Pose2& p)
{
  pose2d_t m;
  m.x = p.x();
  m.y = p.y();
  m.theta = p.theta();
  return m;
}

inline Eigen::Vector2d to_vector(const point2d_t& m) { return {m.x, m.y}; }

inline point2d_t to_point_msg(const Eigen::Vector2d& v)
{
  point2d_t m;
  m.x = v.x();
  m.y = v.y();
  return m;
}

// The one laser_scan_t <-> sensors::LaserScan pair. Floats widen exactly to the scan's double
// fields; on the way out they are rounded to float. Intensities are not kept (no sensor of this
// robot reports them): the message goes out with none.
sensors::LaserScan to_laser_scan(const laser_scan_t& m);
laser_scan_t to_msg(const sensors::LaserScan& s);

}  // namespace rgnav::msg
