// The narrowing test for new line gateways (narrowing.h): a door between rooms is one, a cut
// across a hallway as narrow as a door is not (issue 33: the detector's narrow passages along
// 1.2-1.5 m hallways cut them into a region per stretch).
#include "procs/rg_kernel/narrowing.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "kernel_drive.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;
using testing::Drive;

std::vector<rgmap::LineSegment> segments(const std::vector<rgnav::testing::Wall>& walls)
{
  std::vector<rgmap::LineSegment> out;
  for (const auto& w : walls) {
    rgmap::LineSegment s;
    s.a = w.a;
    s.b = w.b;
    out.push_back(s);
  }
  return out;
}

// A 1.2 m hallway y in [0, 1.2] along x in [0, 12], a door-wide gap in its north wall at x in [6.5, 7.5].
std::vector<rgnav::testing::Wall> narrow_hallway()
{
  using V = Vector2d;
  return {{V(0, 0), V(12, 0)}, {V(0, 1.2), V(6.5, 1.2)}, {V(7.5, 1.2), V(12, 1.2)}, {V(0, 0), V(0, 1.2)},
          {V(12, 0), V(12, 1.2)}, {V(6.5, 1.2), V(6.5, 4)}, {V(7.5, 1.2), V(7.5, 4)}, {V(6.5, 4), V(7.5, 4)}};
}

TEST(Narrowing, DoorBetweenRoomsIsOne)
{
  const NarrowingOptions o;
  const auto n = narrowing_profile(Vector2d(4, 1), Vector2d(4, 2), Vector2d(1, 0), segments(testing::two_rooms()), o);
  EXPECT_TRUE(n.narrowing);
  EXPECT_NEAR(n.width, 1.0, 1e-9);
  EXPECT_NEAR(n.before, 3.0, 1e-6);   // room A's height
  EXPECT_NEAR(n.after, 3.0, 1e-6);
}

TEST(Narrowing, CutAcrossAHallwayIsNone)
{
  // The detector's points on the hallway's walls, 1.2 m apart: the hallway is as wide before and
  // after. Beside the gap in the north wall one side is wider (the closet behind), the other not.
  const NarrowingOptions o;
  const auto walls = segments(narrow_hallway());
  for (const double x : {3.0, 6.0, 8.0}) {
    const auto n = narrowing_profile(Vector2d(x, 0), Vector2d(x, 1.2), Vector2d(1, 0), walls, o);
    EXPECT_FALSE(n.narrowing) << x;
    EXPECT_NEAR(std::min(n.before, n.after), 1.2, 1e-6) << x;
  }
  // Off, every line is a narrowing.
  NarrowingOptions off;
  off.max_width_ratio = 0;
  EXPECT_TRUE(narrowing_profile(Vector2d(3, 0), Vector2d(3, 1.2), Vector2d(1, 0), walls, off).narrowing);
}

TEST(Narrowing, GapIntoASpaceAsNarrowIsNone)
{
  // The gap in the hallway's wall crossed northwards: the hallway's length on one side, the 2.8 m
  // deep closet behind (1 m wide: as wide as the door, so only the hallway side widens) ...
  const NarrowingOptions o;
  const auto n = narrowing_profile(Vector2d(6.5, 1.2), Vector2d(7.5, 1.2), Vector2d(0, 1), segments(narrow_hallway()), o);
  EXPECT_GT(n.before, 10.0);
  EXPECT_NEAR(n.after, 1.0, 1e-6);
  EXPECT_FALSE(n.narrowing);   // ... is no narrowing: the closet is the door's continuation
}

// Along the 1.2 m hallway eastwards; the detector reports a narrow passage across it at x = 4.
void along_the_hallway(Drive& d)
{
  d.walls = narrow_hallway();
  for (double x = 0.6; x < 4.6; x += 0.2) d.scan_at(geometry::Pose2(x, 0.6, 0));
  d.traverse(rgmap::GatewayClass::kNarrowPassage, 7, geometry::Pose2(4.6, 0.6, 0), {Vector2d(4, 0), Vector2d(4, 1.2)});
  for (double x = 4.8; x < 11.0; x += 0.2) d.scan_at(geometry::Pose2(x, 0.6, 0));
}

TEST(RgKernel, NarrowPassageAlongAHallwayIsNoGateway)
{
  Drive d;
  along_the_hallway(d);
  EXPECT_EQ(d.kernel.map().gateways().size(), 0u);
  EXPECT_EQ(d.kernel.stats().regions, 1);

  // Without the test the report cuts the hallway in two.
  KernelOptions off;
  off.narrowing.max_width_ratio = 0;
  Drive before(off);
  along_the_hallway(before);
  EXPECT_EQ(before.kernel.map().gateways().size(), 1u);
  EXPECT_EQ(before.kernel.stats().regions, 2);
}

}  // namespace
}  // namespace rgnav::rg_kernel
