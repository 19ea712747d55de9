#include "procs/rg_kernel/rg_kernel_conversions.h"
#include "procs/rg_kernel/laser_points.h"

#include <cmath>

#include "msg/conversions.h"

namespace rgnav::rg_kernel {

ScanInput to_input(const aligned_scan_t& m)
{
  ScanInput s;
  s.scan_id = m.scan_id;
  s.utime = m.utime;
  s.revision = m.revision;
  s.map_from_base = msg::to_pose2(m.map_from_base);
  s.base_from_laser = msg::to_pose2(m.base_from_laser);
  s.laser_points = laser_points(msg::to_laser_scan(m.scan));
  return s;
}

GatewayEventInput to_input(const gateway_event_t& m)
{
  GatewayEventInput e;
  e.utime = m.utime;
  e.scan_id = m.scan_id;
  e.kind = static_cast<GatewayEventInput::Kind>(m.event);
  e.track_id = m.track_id;
  e.cls = static_cast<rgmap::GatewayClass>(m.gateway_class);
  e.map_from_base = msg::to_pose2(m.map_from_base);
  for (const auto& p : m.gateway_points) e.gateway_points.push_back(msg::to_vector(p));
  e.direction = m.direction;
  return e;
}

}  // namespace rgnav::rg_kernel
