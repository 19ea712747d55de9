// A crossing gone straight through between walls is no gateway (issue 8, office world: the
// detector took doors in the hallway walls for junction branches and cut hall_a_west in three).
#include <gtest/gtest.h>

#include "kernel_drive.h"
#include "procs/rg_kernel/gateway_geometry.h"

namespace rgnav::rg_kernel {
namespace {

using Eigen::Vector2d;
using testing::Drive;
using testing::Wall;

rgmap::LineSegment segment(Vector2d a, Vector2d b) { return {a, b, 0.01, 20}; }

TEST(GatewayGeometry, WidestOpeningIsTheLongestStretchNoWallRunsAlong)
{
  const Line side{Vector2d(0, 0), Vector2d(3, 0)};
  EXPECT_DOUBLE_EQ(widest_opening(side, {}, 0.25), 3.0);
  // Walls along it (a few cm off its line) at both ends leave the middle metre open.
  const std::vector<rgmap::LineSegment> walls{segment({-1, 0.1}, {1, 0.1}), segment({3.5, -0.05}, {2, -0.05})};
  EXPECT_NEAR(widest_opening(side, walls, 0.25), 1.0, 1e-9);
  // A wall across it, one too far from its line, or one at 30 degrees walls nothing.
  const std::vector<rgmap::LineSegment> others{segment({1.5, -1}, {1.5, 1}), segment({0, 0.5}, {3, 0.5}),
                                                segment({0, 0}, {1.5, 0.866})};
  EXPECT_DOUBLE_EQ(widest_opening(side, others, 0.25), 3.0);
}

// A 2 m hallway y in [0, 2] along x in [0, 12] with the given gaps in its south and north walls
// (each gap [x0, x1] leads into a space behind it: a room, or a branch hallway).
std::vector<Wall> hallway(const std::vector<std::pair<double, double>>& south, const std::vector<std::pair<double, double>>& north)
{
  std::vector<Wall> w{{Vector2d(0, 0), Vector2d(0, 2)}, {Vector2d(12, 0), Vector2d(12, 2)}};
  auto side = [&](const std::vector<std::pair<double, double>>& gaps, double y, double behind) {
    double x = 0;
    for (const auto& [x0, x1] : gaps) {
      w.push_back({Vector2d(x, y), Vector2d(x0, y)});
      x = x1;
      // The space behind the gap, 3 m deep and 1 m wider than it each side.
      w.push_back({Vector2d(x0 - 1, y), Vector2d(x0 - 1, y + behind)});
      w.push_back({Vector2d(x1 + 1, y), Vector2d(x1 + 1, y + behind)});
      w.push_back({Vector2d(x0 - 1, y + behind), Vector2d(x1 + 1, y + behind)});
    }
    w.push_back({Vector2d(x, y), Vector2d(12, y)});
  };
  side(south, 0, -3);
  side(north, 2, 3);
  return w;
}

// Drives east along the hallway's centre line and reports a crossing outline x in [5, 7.4].
bool drive_through_crossing(Drive& d)
{
  for (double x = 1.0; x < 7.7; x += 0.2) d.scan_at(geometry::Pose2(x, 1, 0));
  return d.traverse(rgmap::GatewayClass::kXCrossing, 7, geometry::Pose2(7.8, 1, 0),
                    {Vector2d(5, 0), Vector2d(5, 2), Vector2d(7.4, 2), Vector2d(7.4, 0)});
}

TEST(RgKernel, CrossingBetweenDoorsInTheHallwayWallsIsNoGateway)
{
  Drive d;
  d.walls = hallway({{5, 6}}, {{6, 7}});   // two 1 m doors, offset as in the office world
  EXPECT_FALSE(drive_through_crossing(d));
  EXPECT_TRUE(d.kernel.map().gateways().empty());
  EXPECT_EQ(d.kernel.stats().regions, 1);
}

TEST(RgKernel, CrossingWithABranchWideOpeningIsAGateway)
{
  Drive d;
  d.walls = hallway({{5.2, 7.2}}, {});   // a 2 m branch to the south
  EXPECT_TRUE(drive_through_crossing(d));
  EXPECT_EQ(d.kernel.map().gateways().size(), 1u);
  EXPECT_EQ(d.kernel.stats().regions, 2);
  // The check can be switched off: then the doors' "crossing" is a gateway as the detector says.
  KernelOptions off;
  off.min_branch_width = 0;
  Drive doors(off);
  doors.walls = hallway({{5, 6}}, {{6, 7}});
  EXPECT_TRUE(drive_through_crossing(doors));
}

}  // namespace
}  // namespace rgnav::rg_kernel
