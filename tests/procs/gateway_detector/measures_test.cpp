#include <gtest/gtest.h>

#include "gateway_detector/features.h"
#include "gateway_detector/measures.h"
#include "gateway_detector/vlm.h"
#include "synthetic.h"

namespace rgnav::gateway_detector {
namespace {

using test::cast;
using test::crossing;

Line through(const Vec2& a, const Vec2& b)
{
  const Vec2 d = (b - a).normalized();
  Vec2 n(-d.y(), d.x());
  double rho = a.dot(n);
  if (rho < 0) { n = -n; rho = -rho; }
  return Line{std::atan2(n.y(), n.x()), rho};
}

// The true VLM of a crossing at [x0, x0 + w] x [-w/2, w/2] seen from the origin.
Vlm true_vlm(double x0, double w)
{
  Vlm v;
  EXPECT_TRUE(make_vlm(through({0, w / 2}, {1, w / 2}), through({0, -w / 2}, {1, -w / 2}),
                       through({x0 + w, 0}, {x0 + w, 1}), through({x0, 0}, {x0, 1}), &v));
  return v;
}

TEST(Features, StraightWallIsOneSegmentAndOneVirtualLine)
{
  const sensors::LaserScan s = cast({{{2, -3}, {2, 3}}}, geometry::Pose2());
  const auto f = extract_features(s, FeatureOptions{});
  ASSERT_EQ(f.segments.size(), 1u);
  EXPECT_NEAR(f.segments[0].line.rho, 2.0, 1e-6);
  EXPECT_NEAR(f.segments[0].line.theta, 0.0, 1e-6);
  EXPECT_EQ(f.virtual_lines.size(), 1u);
}

TEST(Features, CollinearPiecesFormOneVirtualLine)
{
  // A wall with a door gap: two segments, one virtual line.
  const sensors::LaserScan s = cast({{{2, 0.5}, {2, 3}}, {{2, -3}, {2, -0.5}}, {{6, -5}, {6, 5}}}, geometry::Pose2());
  const auto f = extract_features(s, FeatureOptions{});
  int on_wall = 0;
  for (const auto& vl : f.virtual_lines)
    if (std::fabs(vl.line.rho - 2.0) < 0.05) {
      ++on_wall;
      EXPECT_EQ(vl.segments.size(), 2u);
    }
  EXPECT_EQ(on_wall, 1);
}

TEST(Features, DepthSingularitiesAtTheNearSideOfJumps)
{
  // A wall across the whole field of view with a gap: exactly the two gap edges.
  const sensors::LaserScan s = cast({{{2, 0.5}, {2, 20}}, {{2, -20}, {2, -0.5}}, {{6, -5}, {6, 5}}}, geometry::Pose2());
  const auto ds = depth_singularities(s, 0.5);
  ASSERT_EQ(ds.size(), 2u);
  for (const auto& d : ds) {
    EXPECT_NEAR(d.point.x(), 2.0, 1e-6);
    EXPECT_NEAR(std::fabs(d.point.y()), 0.5, 0.05);
  }
}

TEST(Measures, DistanceAndRectangularityOfTheIdealModel)
{
  const Vlm v = true_vlm(2.0, 2.0);
  EXPECT_NEAR(distance_measure(v, 2.0), 1.0, 1e-6);
  EXPECT_NEAR(rectangularity_measure(v), 1.0, 1e-9);
  // Twice too wide: every side that is 4 m long loses sqrt(1) = 1.
  EXPECT_NEAR(distance_measure(v, 1.0), 0.0, 1e-6);
  // One side 2.5 m long against d_hw = 2: w = 1 - sqrt(0.25) = 0.5 for two sides.
  const Vlm longer = true_vlm(2.0, 2.0);
  Vlm l2;
  ASSERT_TRUE(make_vlm(longer.left, longer.right, Line{0.0, 4.5}, longer.hidden, &l2));
  EXPECT_NEAR(distance_measure(l2, 2.0), 0.25 * (0.5 + 1.0 + 0.5 + 1.0), 1e-6);
}

TEST(Measures, RectangularityDropsWithSkew)
{
  Vlm v;
  ASSERT_TRUE(make_vlm(Line{M_PI / 2, 1.0}, Line{-M_PI / 2, 1.0}, Line{0.2, 4.0}, Line{0.0, 2.0}, &v));
  const double wr = rectangularity_measure(v);
  // The tilted front line meets left and right at pi/2 -+ 0.2: deviations sum to 0.4 rad.
  EXPECT_NEAR(wr, 1.0 - 0.4 / (2 * M_PI), 1e-6);
}

TEST(Measures, OnLineAndOverLineFollowTheWalls)
{
  const MeasureOptions o;
  const Vlm v = true_vlm(2.0, 2.0);
  // T-crossing seen from x = -2: the crossing square is [0, 2]; in laser frame at x0 = 2.
  const sensors::LaserScan t = cast(crossing(kT, 2.0), geometry::Pose2(-2.0, 0, 0));
  const Measures m = measure(t, v, o);
  EXPECT_GT(m.on_line[kFrontSector], 0.95);
  EXPECT_LT(m.over_line[kFrontSector], 0.05);
  // Seen from 2 m before the crossing the side branches are viewed at grazing angles: the
  // branch's far wall stops the beams near the far corner before they pass l_par.
  EXPECT_GT(m.over_line[kLeftSector], 0.6);
  EXPECT_GT(m.over_line[kRightSector], 0.6);
  EXPECT_LT(m.on_line[kLeftSector], 0.05);
  EXPECT_LT(m.on_line[kRightSector], 0.05);
  const auto w = class_weights(m, o);
  EXPECT_EQ(std::max_element(w.begin(), w.begin() + kNumSequenceClasses) - w.begin(), kT);
  // The weights follow the formula: general + f_gw/3 * (over_l + on_f + over_r).
  EXPECT_NEAR(w[kT], 0.5 * o.f_vlm * (m.w_d + m.w_r) + o.f_gw / 3 * (m.over_line[0] + m.on_line[1] + m.over_line[2]), 1e-12);
}

TEST(Measures, EveryClassWinsOnItsOwnIdealCrossing)
{
  const MeasureOptions o;
  const Vlm v = true_vlm(2.0, 2.0);
  for (int c = 0; c < kNumCrossingClasses; ++c) {
    const test::Walls ws = crossing(c, 2.0);
    const sensors::LaserScan s = cast(ws, geometry::Pose2(-2.0, 0, 0));
    const auto w = class_weights(measure(s, v, o), o);
    EXPECT_EQ(std::max_element(w.begin(), w.end()) - w.begin(), c) << crossing_class_name(c);
  }
}

TEST(Measures, ClutterBeforeTheLineIsLeftOutOfTheSectorWhenAsked)
{
  // A dead end seen from 2 m before its square, with a 0.8 m wide box 0.6 m before the end wall
  // (world x = 2, x = 4 in the laser frame).
  const Vlm v = true_vlm(2.0, 2.0);
  test::Walls ws = crossing(kDeadEnd, 2.0);
  ws.push_back({{1.4, -0.4}, {1.4, 0.4}});
  const sensors::LaserScan s = cast(ws, geometry::Pose2(-2.0, 0, 0));
  MeasureOptions paper;
  MeasureOptions robust;
  robust.exclude_occluded = true;
  const Measures a = measure(s, v, paper), b = measure(s, v, robust);
  // The box hides about a third of the front sector; both variants see that.
  EXPECT_GT(a.occluded[kFrontSector], 0.2);
  EXPECT_LT(a.occluded[kFrontSector], 0.5);
  EXPECT_DOUBLE_EQ(b.occluded[kFrontSector], a.occluded[kFrontSector]);
  // The dissertation's FSM counts the hidden beams as off the wall; left out, the wall is whole.
  EXPECT_NEAR(a.on_line[kFrontSector], 1.0 - a.occluded[kFrontSector], 0.05);
  EXPECT_GT(b.on_line[kFrontSector], 0.95);
  EXPECT_LT(b.over_line[kFrontSector], 0.05);
  // Sectors without clutter are the same either way.
  EXPECT_DOUBLE_EQ(a.on_line[kLeftSector], b.on_line[kLeftSector]);
  EXPECT_DOUBLE_EQ(a.occluded[kLeftSector], 0.0);
  // The single-pass sector measure agrees with the separate FSM functions.
  int beams = 0;
  EXPECT_DOUBLE_EQ(on_line_fsm(s, v.front, v.points[1], v.points[2], robust, &beams), b.on_line[kFrontSector]);
  EXPECT_EQ(beams, b.beams[kFrontSector]);
  EXPECT_DOUBLE_EQ(over_line_fsm(s, v.front, v.points[1], v.points[2], robust), b.over_line[kFrontSector]);
}

TEST(Measures, AWhollyHiddenSectorSaysNothing)
{
  // A wall right across the hallway 1 m ahead hides the whole crossing.
  const Vlm v = true_vlm(2.0, 2.0);
  test::Walls ws = crossing(kX, 2.0);
  ws.push_back({{1.0, -1.0}, {1.0, 1.0}});
  const sensors::LaserScan s = cast(ws, geometry::Pose2(0.0, 0, 0));
  MeasureOptions robust;
  robust.exclude_occluded = true;
  const Measures m = measure(s, v, robust);
  for (int sec = 0; sec < 3; ++sec) {
    if (m.beams[static_cast<size_t>(sec)] == 0) continue;
    EXPECT_DOUBLE_EQ(m.occluded[static_cast<size_t>(sec)], 1.0) << sec;
    EXPECT_DOUBLE_EQ(m.on_line[static_cast<size_t>(sec)], 0.0) << sec;
    EXPECT_DOUBLE_EQ(m.over_line[static_cast<size_t>(sec)], 0.0) << sec;
  }
  EXPECT_GT(m.beams[kFrontSector], 0);
}

TEST(Measures, ALargerSetbackTellsAWallBehindClutterFromAnOpening)
{
  // Clutter along the left wall (cabinet faces at y = 0.6, the wall at y = 1) taken for the
  // left line of a crossing at [2, 4] ahead: the wall 0.4 m behind that line passes a 0.25 m
  // setback line as if the side were open, but not a 0.6 m one; a real side branch does.
  Vlm v;
  ASSERT_TRUE(make_vlm(through({0, 0.6}, {1, 0.6}), through({0, -1}, {1, -1}), through({4, 0}, {4, 1}), through({2, 0}, {2, 1}), &v));
  const sensors::LaserScan closed = cast({{{-10, 1}, {10, 1}}, {{-10, -1}, {10, -1}}}, geometry::Pose2());
  const sensors::LaserScan open = cast(crossing(kT, 2.0), geometry::Pose2(-2.0, 0, 0));
  MeasureOptions near_setback, far_setback;
  far_setback.over_line_setback = 0.6;
  EXPECT_GT(measure(closed, v, near_setback).over_line[kLeftSector], 0.95);
  EXPECT_LT(measure(closed, v, far_setback).over_line[kLeftSector], 0.05);
  EXPECT_GT(measure(open, true_vlm(2.0, 2.0), far_setback).over_line[kLeftSector], 0.3);
}

}  // namespace
}  // namespace rgnav::gateway_detector
