#include <gtest/gtest.h>

#include "geometry/pose2.h"
#include "msg/conversions.h"

namespace rgnav::geometry {
namespace {

void expect_near(const Pose2& a, const Pose2& b)
{
  EXPECT_NEAR(a.x(), b.x(), 1e-12);
  EXPECT_NEAR(a.y(), b.y(), 1e-12);
  EXPECT_NEAR(normalize_angle(a.theta() - b.theta()), 0.0, 1e-12);
}

TEST(Pose2, ComposeReadsLeftToRight)
{
  const Pose2 world_from_robot(1, 2, M_PI / 2);
  const Pose2 robot_from_laser(0.1, 0, 0);
  const Pose2 world_from_laser = world_from_robot * robot_from_laser;
  expect_near(world_from_laser, Pose2(1, 2.1, M_PI / 2));
  const Eigen::Vector2d p = world_from_laser * Eigen::Vector2d(1, 0);
  EXPECT_NEAR(p.x(), 1, 1e-12);
  EXPECT_NEAR(p.y(), 3.1, 1e-12);
}

TEST(Pose2, InverseAndBetween)
{
  const Pose2 a(3, -1, 2.5), b(-2, 4, -3.0);
  expect_near(a * a.inverse(), Pose2());
  expect_near(a * a.between(b), b);
}

TEST(Pose2, AngleNormalised)
{
  EXPECT_NEAR(Pose2(0, 0, 3 * M_PI).theta(), M_PI, 1e-12);
  EXPECT_NEAR(normalize_angle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(normalize_angle(7.0), 7.0 - 2 * M_PI, 1e-12);
}

TEST(Conversions, PoseRoundTrip)
{
  const Pose2 p(1.5, -2.25, 0.75);
  expect_near(msg::to_pose2(msg::to_msg(p)), p);
  const Eigen::Vector2d v(3, 4);
  EXPECT_EQ(msg::to_vector(msg::to_point_msg(v)), v);
}

}  // namespace
}  // namespace rgnav::geometry
