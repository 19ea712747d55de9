#include "procs/rg_kernel/rg_kernel_conversions.h"
#include "procs/rg_kernel/laser_points.h"

#include <cmath>

#include "msg/conversions.h"
#include "rgmap/rgmap_conversions.h"

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

std::vector<rgmap::Rectangle3d> to_rectangles(const objects3d_t& m, const geometry::Pose2& map_from_base, std::string* why)
{
  std::vector<rgmap::Rectangle3d> out;
  for (const auto& x : m.rectangles) {
    rgmap::Rectangle3d r = rgmap::from_msg(x);
    const bool plausible = r.corners.allFinite() && r.normal.allFinite() && r.corners.cwiseAbs().maxCoeff() < 100.0 &&
                           std::isfinite(r.width) && std::isfinite(r.height) && r.width > 0.0 && r.width <= 10.0 &&
                           r.height > 0.0 && r.height <= 10.0 && r.normal.norm() > 0.5;
    if (!plausible) {
      if (why) *why = "rectangle " + std::to_string(x.id) + " is no plausible rectangle";
      return {};
    }
    r.normal.normalize();
    out.push_back(rgmap::moved(r, map_from_base));
  }
  return out;
}

}  // namespace rgnav::rg_kernel
