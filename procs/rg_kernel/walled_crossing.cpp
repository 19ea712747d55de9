// A crossing traversal between walls (part of RgKernel, rg_kernel.h): the gateway detector's
// junction hypotheses (diss. 4.1) take a door in a hallway wall for a branch, and a room's wall
// seen through a door for the junction's far side. Gone straight through, such a "junction"
// cut the hallway in two at a place no wall narrows (false crossings along a hallway lined with
// open doors). A real branch opens its side about as wide as a hallway; a door, at most 1.3 m.
#include <cmath>
#include <vector>

#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/rg_kernel.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

bool RgKernel::walled_crossing(const GatewayEventInput& e, int64_t current) const
{
  if (e.gateway_points.size() != 4 || options_.min_branch_width <= 0) return false;
  const geometry::Pose2 region_from_map = map_.region(current)->map_from_region.inverse();
  std::vector<Vector2d> outline;
  for (const auto& p : e.gateway_points) outline.push_back(region_from_map * p);
  const Vector2d heading = region_from_map.rotation() * Vector2d(std::cos(e.direction), std::sin(e.direction));
  const OpeningTest opening{options_.min_branch_width, options_.branch_wall_tolerance};
  const auto& walls = builders_.at(current).segments();
  int sides = 0;
  for (const EdgeFrame& f : edge_frames(outline)) {
    if (std::fabs(f.along.dot(heading)) < std::cos(M_PI / 4)) continue;   // the entry or exit side
    ++sides;
    if (opening.open(f, walls)) return false;
  }
  return sides > 0;
}

}  // namespace rgnav::rg_kernel
