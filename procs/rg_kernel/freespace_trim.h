// A region's freespace without what its robot only saw through a narrow passage (issue 8: a
// room entered from the room next door looks out through its own door, never gone through and
// unknown as a gateway, and took a wedge of the hallway; the line map's doorway test misses
// doors beside furniture). The cells where a disk of the passage's half width fits are split
// into components; those a robot position lies at are the region's own space, given back out to
// twice the radius (the disks, then their border); the rest lies behind a passage narrower than
// the disk.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace rgnav::rg_kernel {

using Cell = std::pair<int32_t, int32_t>;

// `cells`: free cells; `origins`: cells the region's robot stood in; `radius`: the disk's radius
// in cells (a passage narrower than 2 * radius + 1 cells is cut). Returns the cells kept, in
// the order given; all of `cells` if no robot position lies within twice the radius of a place
// where the disk fits (a region of narrow passages only).
std::vector<Cell> trim_seen_through(const std::vector<Cell>& cells, const std::vector<Cell>& origins, int radius);

}  // namespace rgnav::rg_kernel
