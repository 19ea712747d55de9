#include "trajectory/construct.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rgnav::trajectory {
namespace {

void expect_connects(const Chain& c, const Pose2& start, const Pose2& end, double tol = 1e-7)
{
  ASSERT_FALSE(c.empty());
  EXPECT_NEAR((c.start().translation() - start.translation()).norm(), 0.0, tol);
  EXPECT_NEAR((c.end().translation() - end.translation()).norm(), 0.0, tol);
  EXPECT_NEAR(geometry::normalize_angle(c.end().theta() - end.theta()), 0.0, tol);
  const auto cont = c.continuity();
  EXPECT_LT(cont.position, tol);
  EXPECT_LT(cont.heading, tol);
}

TEST(Construct, LineArcLine)
{
  const Pose2 a(0, 0, 0), b(3, 2, M_PI / 2);
  const auto c = line_arc_line(a, b, 5.0);
  ASSERT_TRUE(c);
  expect_connects(*c, a, b);
  // Shorter leg is 2 m: radius 2 after 1 m of line.
  EXPECT_EQ(c->size(), 2u);
  EXPECT_NEAR((*c)[1].kappa0(), 0.5, 1e-12);
  EXPECT_FALSE(line_arc_line(a, Pose2(-1, 2, M_PI / 2), 5.0));  // corner behind the start
}

TEST(Construct, LineTurnLineIsG2)
{
  const Pose2 a(1, 1, 0.3), b(3.5, 3.0, 1.9);
  const auto c = line_turn_line_g2(a, b, 5.0);
  ASSERT_TRUE(c);
  expect_connects(*c, a, b);
  EXPECT_LT(c->continuity().curvature, 1e-9);
  EXPECT_NEAR(c->curvature_at(0.0), 0.0, 1e-12);
  EXPECT_NEAR(c->curvature_at(c->length()), 0.0, 1e-12);
}

TEST(Construct, ClothoidG1Hermite)
{
  const Pose2 pairs[][2] = {
      {Pose2(0, 0, 0), Pose2(2, 1, 0)},            // S-bend
      {Pose2(0, 0, 0), Pose2(1.5, 1.5, M_PI / 2)},  // quarter turn
      {Pose2(1, -1, 2.0), Pose2(0, 1, 2.5)},
      {Pose2(0, 0, 0), Pose2(2, 0, 0)},             // straight
  };
  for (const auto& p : pairs) {
    const auto seg = clothoid_g1(p[0], p[1]);
    ASSERT_TRUE(seg);
    expect_connects(Chain({*seg}), p[0], p[1], 1e-8);
  }
}

TEST(Construct, SmoothTurn)
{
  const Chain c = smooth_turn(Pose2(0, 0, 0), -M_PI / 2, 2.0);
  EXPECT_NEAR(c.end().theta(), -M_PI / 2, 1e-12);
  EXPECT_LT(c.continuity().curvature, 1e-12);
}

TEST(Construct, DubinsReachesPose)
{
  const Pose2 start(0, 0, 0);
  for (const Pose2& end : {Pose2(4, 1, 0), Pose2(0.5, 0.2, M_PI), Pose2(-2, 3, -1.0), Pose2(3, -3, 2.5)}) {
    const auto c = dubins(start, end, 1.0);
    ASSERT_TRUE(c);
    expect_connects(*c, start, end, 1e-7);
  }
  // Straight ahead: the line itself.
  const auto c = dubins(start, Pose2(5, 0, 0), 1.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->length(), 5.0, 1e-9);
}

TEST(Construct, QuarterEllipse)
{
  const auto e = quarter_ellipse(Pose2(1, 1, M_PI / 2), Pose2(0.5, 3, M_PI));
  ASSERT_TRUE(e);
  expect_connects(Chain({*e}), Pose2(1, 1, M_PI / 2), Pose2(0.5, 3, M_PI), 1e-8);
  EXPECT_FALSE(quarter_ellipse(Pose2(), Pose2(1, 1, 0.3)));
}

}  // namespace
}  // namespace rgnav::trajectory
