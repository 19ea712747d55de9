// Drives an RgKernel through testing::two_rooms() (or other walls): scans cast at given poses
// and gateway events as the detector reports them.
#pragma once

#include <utility>
#include <vector>

#include "procs/rg_kernel/rg_kernel.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel::testing {

struct Drive
{
  explicit Drive(KernelOptions options = {}) : kernel(std::move(options)) {}

  RgKernel kernel;
  std::vector<Wall> walls = two_rooms();
  int64_t next_id = 1;
  int64_t t = 1'000'000;

  void scan_at(const geometry::Pose2& pose)
  {
    ScanInput s;
    s.scan_id = next_id++;
    s.utime = (t += 200'000);
    s.map_from_base = pose;
    s.laser_points = cast(walls, pose);
    kernel.add_scan(s);
  }
  // The detector reports the robot traversed a gateway with these points, now at `robot`.
  bool traverse(rgmap::GatewayClass cls, int64_t track_id, const geometry::Pose2& robot,
                std::vector<Eigen::Vector2d> gateway_points)
  {
    GatewayEventInput e;
    e.utime = (t += 1000);
    e.kind = GatewayEventInput::Kind::kTraversed;
    e.track_id = track_id;
    e.cls = cls;
    e.map_from_base = robot;
    e.gateway_points = std::move(gateway_points);
    e.direction = robot.theta();
    return kernel.add_gateway_event(e);
  }
  // The door of two_rooms() at x = 4, y in [1, 2].
  void traverse_door(double x, double heading)
  {
    traverse(rgmap::GatewayClass::kDoor, 1, geometry::Pose2(x, 1.5, heading), {Eigen::Vector2d(4, 1), Eigen::Vector2d(4, 2)});
  }
};

// Free cells (0.1 m) of region 1's freespace inside room B of two_rooms(), region 1's frame
// being the first pose (1, 1.5): what beams through the doorway carved into room A's region.
inline int room_b_cells_of_region_1(const RgKernel& kernel)
{
  const auto r1 = kernel.describe_region(1);
  int n = 0;
  for (double x = 4.35; x < 8.0; x += 0.1)
    for (double y = 0.05; y < 3.0; y += 0.1) n += r1.freespace.is_free(Eigen::Vector2d(x - 1.0, y - 1.5)) ? 1 : 0;
  return n;
}

}  // namespace rgnav::rg_kernel::testing
