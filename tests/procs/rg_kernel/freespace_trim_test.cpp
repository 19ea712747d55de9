// What a region's robot saw only through a narrow passage is cut from its freespace.
#include <gtest/gtest.h>

#include <algorithm>

#include "procs/rg_kernel/freespace_trim.h"

namespace rgnav::rg_kernel {
namespace {

// A 27 x 27 cell room (4 m at 0.15 m), a door 6 cells wide (0.9 m) and 3 long through its east
// wall, and 30 x 27 cells of hallway beyond it.
std::vector<Cell> room_door_hallway()
{
  std::vector<Cell> cells;
  for (int32_t y = 0; y < 27; ++y)
    for (int32_t x = 0; x < 60; ++x) {
      const bool door = x >= 27 && x < 30 && y >= 10 && y < 16;
      if (x < 27 || door || x >= 30) cells.emplace_back(x, y);
    }
  return cells;
}

int count(const std::vector<Cell>& cells, int32_t x_from, int32_t x_to)
{
  return static_cast<int>(std::count_if(cells.begin(), cells.end(), [&](const Cell& c) { return c.first >= x_from && c.first < x_to; }));
}

TEST(FreespaceTrim, SpaceSeenOnlyThroughADoorIsCut)
{
  const auto cells = room_door_hallway();
  const auto kept = trim_seen_through(cells, {{10, 10}, {15, 20}}, 3);
  EXPECT_EQ(count(kept, 0, 27), 27 * 27);   // the room whole, corners included
  EXPECT_EQ(count(kept, 27, 30), 3 * 6);    // the door
  EXPECT_EQ(count(kept, 36, 60), 0);        // of the hallway nothing more than 6 cells (0.9 m) past the wall,
  EXPECT_LT(count(kept, 30, 36), 6 * 12);   // and there only the door's mouth
}

TEST(FreespaceTrim, SpaceTheRobotStoodInStays)
{
  const auto cells = room_door_hallway();
  // The robot went through the door: both sides are the region's.
  EXPECT_EQ(trim_seen_through(cells, {{10, 10}, {45, 12}}, 3).size(), cells.size());
  // A passage wider than the disk is no cut: radius 2 (0.75 m) against the 0.9 m door.
  EXPECT_EQ(trim_seen_through(cells, {{10, 10}}, 2).size(), cells.size());
  // Off.
  EXPECT_EQ(trim_seen_through(cells, {{10, 10}}, 0).size(), cells.size());
}

TEST(FreespaceTrim, ARegionOfNarrowPassagesOnlyKeepsItsCells)
{
  // A 4-cell wide corridor: the opening keeps nothing, so nothing is cut.
  std::vector<Cell> corridor;
  for (int32_t x = 0; x < 40; ++x)
    for (int32_t y = 0; y < 4; ++y) corridor.emplace_back(x, y);
  EXPECT_EQ(trim_seen_through(corridor, {{5, 2}}, 3).size(), corridor.size());
}

}  // namespace
}  // namespace rgnav::rg_kernel
