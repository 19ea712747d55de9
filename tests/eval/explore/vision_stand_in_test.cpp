#include "vision_stand_in.h"

#include <gtest/gtest.h>

namespace rgnav::explore_eval {
namespace {

using Eigen::Vector2d;
using geometry::Pose2;

// A table 2 m ahead of the robot at the origin (looking along +x), a cabinet the laser sees
// beside it, and, behind a wall to the robot's left, another table.
sim::World world()
{
  sim::World w;
  sim::Table ahead;
  ahead.name = "ahead";
  ahead.center = Vector2d(2.3, 0.0);
  ahead.size = Vector2d(0.8, 0.8);
  w.tables.push_back(ahead);
  sim::Box cabinet;
  cabinet.name = "cabinet";
  cabinet.center = Vector2d(2.0, 1.0);
  cabinet.size = Vector2d(0.4, 0.4);
  cabinet.z_min = 0.0;
  cabinet.z_max = 1.9;
  w.boxes.push_back(cabinet);
  sim::Table hidden = ahead;
  hidden.name = "hidden";
  hidden.center = Vector2d(1.5, 2.0);
  w.tables.push_back(hidden);
  sim::Wall wall;
  wall.a = Vector2d(-1.0, 1.5);
  wall.b = Vector2d(4.0, 1.5);
  w.walls.push_back(wall);
  return w;
}

TEST(VisionStandIn, GivesTheTableTopInViewAndRemembersItButNotWhatTheLaserSeesOrAWallHides)
{
  VisionStandIn v(world(), VisionStandInOptions{});
  ASSERT_GT(v.samples(), 0u);
  // The robot at the origin looking ahead; odometry 1 m off the world frame.
  const Pose2 odom_from_world(1.0, 0.0, 0.0);
  auto odom = [&](const Pose2& world_from_base) { return odom_from_world * world_from_base; };
  const Pose2 here(0, 0, 0);
  ASSERT_TRUE(v.due(0.0));
  const auto points = v.update(0.0, here, odom(here));
  ASSERT_FALSE(points.empty());
  for (const auto& p : points) {
    const Vector2d w = odom_from_world.inverse() * p;   // back to the world frame
    EXPECT_NEAR(w.y(), 0.0, 0.45) << "only the table ahead: not the cabinet (the laser's) nor the hidden table";
    EXPECT_GT(w.x(), 1.8);
    EXPECT_LT(w.x(), 2.8);
  }
  EXPECT_FALSE(v.due(0.1));
  // Turned away: what was seen stays (the OctoMap's memory).
  const Pose2 away(0, 0, M_PI);
  EXPECT_EQ(v.update(0.2, away, odom(away)).size(), points.size());
  // Far away: outside the grid round the robot.
  const Pose2 far(20, 0, 0);
  EXPECT_TRUE(v.update(0.4, far, odom(far)).empty());
}

}  // namespace
}  // namespace rgnav::explore_eval
