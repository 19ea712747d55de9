#include "trajectory/chain.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rgnav::trajectory {
namespace {

TEST(Segment, LineAndArcAnalytic)
{
  const Pose2 start(1.0, 2.0, M_PI / 2);
  const Segment line = Segment::line(start, 3.0);
  EXPECT_NEAR(line.end().x(), 1.0, 1e-12);
  EXPECT_NEAR(line.end().y(), 5.0, 1e-12);
  // Quarter circle of radius 2 to the left: from (0,0) heading +x to (2,2) heading +y.
  const Segment arc = Segment::arc(Pose2(), 0.5, M_PI);
  EXPECT_NEAR(arc.end().x(), 2.0, 1e-12);
  EXPECT_NEAR(arc.end().y(), 2.0, 1e-12);
  EXPECT_NEAR(arc.end().theta(), M_PI / 2, 1e-12);
  EXPECT_NEAR(arc.heading_change(), M_PI / 2, 1e-12);
  const Pose2 mid = arc.pose_at(M_PI / 2);  // 45 deg around
  EXPECT_NEAR(mid.x(), 2.0 * std::sin(M_PI / 4), 1e-12);
  EXPECT_NEAR(mid.y(), 2.0 - 2.0 * std::cos(M_PI / 4), 1e-12);
  // Right turn.
  const Segment right = Segment::arc(Pose2(), -0.5, M_PI);
  EXPECT_NEAR(right.end().y(), -2.0, 1e-12);
}

TEST(Segment, ClothoidHeadingAndCurvature)
{
  const Segment c = Segment::clothoid(Pose2(0.5, -1.0, 0.3), 0.2, 1.4, 2.0);
  EXPECT_NEAR(c.curvature_at(1.0), 0.8, 1e-12);
  EXPECT_NEAR(c.end().theta(), 0.3 + 0.5 * (0.2 + 1.4) * 2.0, 1e-12);
  // Numerical derivative of position equals the heading direction.
  const double s = 1.2, h = 1e-5;
  const Pose2 a = c.pose_at(s - h), b = c.pose_at(s + h), m = c.pose_at(s);
  const Eigen::Vector2d d = (b.translation() - a.translation()) / (2 * h);
  EXPECT_NEAR(d.x(), std::cos(m.theta()), 1e-8);
  EXPECT_NEAR(d.y(), std::sin(m.theta()), 1e-8);
}

TEST(Segment, ConicQuarterEllipse)
{
  // Semi-axes 2 (forward) and 1 (left): start at the bottom of the ellipse heading +x.
  const double a = 2.0, b = 1.0;
  const double quarter = ellipse_arc_length(a, b, -M_PI / 2, 0.0);
  EXPECT_NEAR(quarter, 2.4221120551, 1e-9);  // quarter of Ramanujan-checked perimeter 9.6884482205
  const Segment e = Segment::conic(Pose2(), a, b, -M_PI / 2, true, quarter);
  EXPECT_NEAR(e.end().x(), 2.0, 1e-9);
  EXPECT_NEAR(e.end().y(), 1.0, 1e-9);
  EXPECT_NEAR(e.end().theta(), M_PI / 2, 1e-9);
  EXPECT_NEAR(e.kappa0(), b / (a * a), 1e-9);  // at the co-vertex (0, -b): b / a^2
  EXPECT_NEAR(e.kappa1(), a / (b * b), 1e-9);  // at the vertex (a, 0): a / b^2
  EXPECT_NEAR(e.heading_change(), M_PI / 2, 1e-9);
}

TEST(Segment, TurnInPlace)
{
  const Segment t = Segment::turn(Pose2(1, 1, 0.2), -1.0);
  EXPECT_EQ(t.length(), 0.0);
  EXPECT_NEAR(t.end().theta(), -0.8, 1e-12);
  EXPECT_NEAR(t.end().x(), 1.0, 1e-12);
}

TEST(Segment, ProjectionGivesCrossTrack)
{
  const Segment arc = Segment::arc(Pose2(), 0.5, M_PI);  // radius 2, centre (0, 2)
  // A point 0.1 m outside the circle at 30 deg: lateral -0.1 (right of a left turn).
  const double ang = M_PI / 6;
  const Eigen::Vector2d p(2.1 * std::sin(ang), 2.0 - 2.1 * std::cos(ang));
  const Projection pr = project(arc, p, 0.0, arc.length());
  EXPECT_NEAR(pr.s, 2.0 * ang, 1e-9);
  EXPECT_NEAR(pr.lateral, -0.1, 1e-9);
  // Same for a clothoid (numerical): offset along the normal is recovered.
  const Segment c = Segment::clothoid(Pose2(), 0.0, 2.0, 1.5);
  const Pose2 q = c.pose_at(0.9);
  const Eigen::Vector2d n(-std::sin(q.theta()), std::cos(q.theta()));
  const Projection pc = project(c, q.translation() + 0.05 * n, 0.0, c.length());
  EXPECT_NEAR(pc.s, 0.9, 1e-7);
  EXPECT_NEAR(pc.lateral, 0.05, 1e-7);
  // And an ellipse.
  const Segment e = Segment::conic(Pose2(), 2.0, 1.0, -M_PI / 2, true, 2.0);
  const Pose2 r = e.pose_at(1.1);
  const Eigen::Vector2d ne(-std::sin(r.theta()), std::cos(r.theta()));
  const Projection pe = project(e, r.translation() - 0.03 * ne, 0.0, e.length());
  EXPECT_NEAR(pe.s, 1.1, 1e-6);
  EXPECT_NEAR(pe.lateral, -0.03, 1e-7);
}

TEST(Chain, ContinuityAndLookup)
{
  Chain c;
  c.push_back(Segment::line(Pose2(), 1.0));
  c.append_at_end(Segment::clothoid(Pose2(), 0.0, 1.0, 0.5));
  c.append_at_end(Segment::arc(Pose2(), 1.0, 0.5));
  c.append_at_end(Segment::turn(Pose2(), 0.5));
  c.append_at_end(Segment::line(Pose2(), 0.7));
  EXPECT_NEAR(c.length(), 2.7, 1e-12);
  const auto cont = c.continuity();
  EXPECT_LT(cont.position, 1e-12);
  EXPECT_LT(cont.heading, 1e-12);
  EXPECT_LT(cont.curvature, 1e-12 + 1.0);  // arc -> line after the turn is not counted
  EXPECT_EQ(c.segment_at(0.5), 0u);
  EXPECT_EQ(c.segment_at(1.2), 1u);
  EXPECT_EQ(c.segment_at(2.1), 4u);  // past the turn
  // Pose continuity across the joints.
  for (double s : {1.0, 1.5, 2.0}) {
    const Pose2 a = c.pose_at(s - 1e-9), b = c.pose_at(s + 1e-9);
    EXPECT_NEAR((a.translation() - b.translation()).norm(), 0.0, 1e-8);
  }
  const auto pr = c.project(c.pose_at(1.7).translation(), 0.0, c.length());
  EXPECT_NEAR(pr.s, 1.7, 1e-7);
}

}  // namespace
}  // namespace rgnav::trajectory
