// A crossing traversal between walls (part of RgKernel, rg_kernel.h): the gateway detector's
// junction hypotheses (diss. 4.1) take a door in a hallway wall for a branch, and a room's wall
// seen through a door for the junction's far side. Gone straight through, such a "junction"
// cut the hallway in two at a place no wall narrows (office world: three false crossings in
// hall_a_west). A real branch opens its side about as wide as a hallway; a door, at most 1.3 m.
#include <algorithm>
#include <cmath>

#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/rg_kernel.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

bool RgKernel::walled_crossing(const GatewayEventInput& e, int64_t current) const
{
  if (e.gateway_points.size() != 4 || options_.min_branch_width <= 0) return false;
  const geometry::Pose2 region_from_map = map_.region(current)->map_from_region.inverse();
  const auto& walls = builders_.at(current).segments();
  const Vector2d heading(std::cos(e.direction), std::sin(e.direction));
  int sides = 0;
  for (const EdgeFrame& f : edge_frames(e.gateway_points)) {
    if (std::fabs(f.along.dot(heading)) < std::cos(M_PI / 4)) continue;   // the entry or exit side
    ++sides;
    const Line side{region_from_map * f.line.first, region_from_map * f.line.second};
    const double needed = std::min(options_.min_branch_width, 0.8 * f.length);
    const double open = widest_opening(side, walls, options_.branch_wall_tolerance);
    if (open >= needed) return false;
  }
  return sides > 0;
}

}  // namespace rgnav::rg_kernel
