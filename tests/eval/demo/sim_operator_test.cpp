// The scripted operator names regions after the world's rooms, through the start pose: a map
// point is a world point seen from where the robot started.
#include "sim_operator.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rgnav::demo {
namespace {

sim::World two_rooms()
{
  sim::World w;
  w.start = {10.0, 2.0, M_PI / 2};   // at (10, 2), looking along +y
  sim::Region a;
  a.name = "kitchen";
  a.polygon = {{8, 0}, {12, 0}, {12, 4}, {8, 4}};
  sim::Region b;
  b.name = "hall";
  b.kind = sim::RegionKind::kHallway;
  b.polygon = {{8, 4}, {12, 4}, {12, 6}, {8, 6}};
  w.regions = {a, b};
  return w;
}

TEST(SimOperator, NamesByTheRoomHoldingTheCentroidInTheWorldFrame)
{
  SimOperator op(two_rooms());
  // Map x is world +y from the start: 3 m ahead is (10, 5), in the hall.
  const sim::Vec2 w = op.to_world(3.0, 0.0);
  EXPECT_NEAR(w.x(), 10.0, 1e-9);
  EXPECT_NEAR(w.y(), 5.0, 1e-9);
  EXPECT_EQ(op.name(2, 3.0, 0.0).name, "hall");
  EXPECT_EQ(op.name(2, 3.0, 0.0).kind, "hallway");
  // Map y is world -x: 1 m to the left of the start is (9, 2), the kitchen.
  EXPECT_EQ(op.name(1, 0.0, 1.0).name, "kitchen");
  // A second region in the kitchen gets a name of its own; asked again, the same answer.
  EXPECT_EQ(op.name(3, 0.5, 0.5).name, "kitchen_2");
  EXPECT_EQ(op.name(1, 0.0, 1.0).name, "kitchen");
  // Just outside every room: the nearest within reach; far away: an area of its own.
  EXPECT_EQ(op.name(4, 0.0, -2.5).name, "kitchen_3");   // (12.5, 2)
  EXPECT_EQ(op.name(5, 0.0, -20.0).name, "area_5");
  EXPECT_EQ(op.name(5, 0.0, -20.0).room, "");
}

}  // namespace
}  // namespace rgnav::demo
