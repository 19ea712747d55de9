// The messages an RG kernel process gets in a synthetic run through testing::two_rooms() (or
// other walls): aligned scans cast at given poses and the detector's door traversals. For the
// node tests and the restart bench, which feed the process over its bus.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "rgnav/aligned_scan_t.hpp"
#include "laser_scan_msg.h"
#include "rgnav/gateway_event_t.hpp"
#include "synthetic_world.h"

namespace rgnav::rg_kernel::testing {

// An aligned scan at `map_from_base` (laser = base, odometry = map): 181 beams over 180 degrees
// cast in `walls` and `pillars`, 8 m where nothing is hit; `range_noise` (if set) is added to
// each beam that hits, in beam order.
inline aligned_scan_t aligned_scan_msg(const std::vector<Wall>& walls, int64_t utime, int64_t scan_id,
                                       const pose2d_t& map_from_base, const std::vector<Pillar>& pillars = {},
                                       const std::function<double()>& range_noise = nullptr)
{
  aligned_scan_t m{};
  m.utime = utime;
  m.scan_id = scan_id;
  m.map_from_base = map_from_base;
  m.odom_from_base = m.map_from_base;
  m.scan = rgnav::testing::laser_scan_msg(utime, scan_id, 8.0f, 8.0f);
  laser_scan_t& s = m.scan;
  const geometry::Pose2 pose(m.map_from_base.x, m.map_from_base.y, m.map_from_base.theta);
  // cast() drops max-range beams; recover each beam's range from its bearing.
  for (const auto& p : cast(walls, pose, 8.0, pillars)) {
    const int beam = static_cast<int>(std::lround((std::atan2(p.y(), p.x()) + M_PI / 2) / (M_PI / 180)));
    if (beam >= 0 && beam < 181)
      s.ranges[static_cast<size_t>(beam)] = static_cast<float>(range_noise ? p.norm() + range_noise() : p.norm());
  }
  return m;
}

// The detector's report that the robot, at (x, 1.5) heading `heading`, traversed the door of
// two_rooms() (x = 4, y in [1, 2]).
inline gateway_event_t door_traversed_msg(int64_t utime, int64_t scan_id, int64_t track_id, double x, double heading)
{
  gateway_event_t e{};
  e.utime = utime;
  e.scan_id = scan_id;
  e.event = gateway_event_t::EVENT_TRAVERSED;
  e.track_id = track_id;
  e.gateway_class = gateway_event_t::CLASS_DOOR;
  e.map_from_base.x = x;
  e.map_from_base.y = 1.5;
  e.map_from_base.theta = heading;
  e.direction = heading;
  e.npoints = 2;
  e.gateway_points.resize(2);
  e.gateway_points[0].x = 4;
  e.gateway_points[0].y = 1;
  e.gateway_points[1].x = 4;
  e.gateway_points[1].y = 2;
  return e;
}

}  // namespace rgnav::rg_kernel::testing
