#include <gtest/gtest.h>

#include "gateway_detector/narrow_passage.h"
#include "gateway_detector/options.h"
#include "synthetic.h"

namespace rgnav::gateway_detector {
namespace {

using test::cast;

TEST(NarrowPassage, ClosestPairGeometry)
{
  // Two posts at (2, +-0.5): D_lr = 1, D_NP = 2, aperture = 2 atan(0.25).
  const sensors::LaserScan s = cast({{{2, 0.5}, {2, 3}}, {{2, -3}, {2, -0.5}}, {{6, -5}, {6, 5}}}, geometry::Pose2());
  const auto cp = closest_pair(s, 0.0, M_PI / 2);
  ASSERT_TRUE(cp);
  EXPECT_NEAR(s.point(cp->left).y(), 0.5, 0.04);
  EXPECT_NEAR(s.point(cp->right).y(), -0.5, 0.04);
  EXPECT_NEAR(cp->d_lr, 1.0, 0.08);
  EXPECT_NEAR(cp->d_np, 2.0, 0.02);
  EXPECT_NEAR(cp->aperture, 2 * std::atan(0.25), 0.04);
}

TEST(NarrowPassage, DoorInFrontIsDetected)
{
  const NarrowPassageOptions o;
  const sensors::LaserScan s = cast(test::door(2.0, 0.9), geometry::Pose2(0.3, 0.05, 0.0), 0.005);
  const auto nps = detect_narrow_passages(s, o);
  ASSERT_EQ(nps.size(), 1u);
  // Beams at 1 deg see the frame within one beam spacing.
  EXPECT_NEAR(nps[0].left.x(), 1.7, 0.05);
  EXPECT_NEAR(nps[0].left.y(), 0.45 - 0.05, 0.05);
  EXPECT_NEAR(nps[0].right.y(), -0.45 - 0.05, 0.05);
  EXPECT_NEAR(nps[0].width, 0.9, 0.1);
}

TEST(NarrowPassage, TableLegsAreNoDoorWhenJambsNeedSurface)
{
  // Two 5 cm legs 1 m apart, 2 m ahead, a wall behind: a passage by the distances of 4.2.1.
  const test::Walls legs = {{{2.0, 0.5}, {2.0, 0.55}}, {{2.0, -0.55}, {2.0, -0.5}}, {{6, -5}, {6, 5}}};
  const sensors::LaserScan s = cast(legs, geometry::Pose2());
  NarrowPassageOptions o;
  const auto between = detect_narrow_passages(s, o);
  ASSERT_EQ(between.size(), 1u);
  EXPECT_LT(surface_extent(s, between[0].left_index, o.jamb_link_distance), 0.1);
  EXPECT_LT(surface_extent(s, between[0].right_index, o.jamb_link_distance), 0.1);
  o.min_jamb_extent = 0.2;
  EXPECT_TRUE(detect_narrow_passages(s, o).empty());
  // A real door frame keeps its passage: its gateway points end walls.
  const sensors::LaserScan d = cast(test::door(2.0, 0.9), geometry::Pose2(0.3, 0.05, 0.0), 0.005);
  const auto nps = detect_narrow_passages(d, o);
  ASSERT_EQ(nps.size(), 1u);
  EXPECT_GT(surface_extent(d, nps[0].left_index, o.jamb_link_distance), 1.0);
}

TEST(NarrowPassage, TooNarrowForTheRobot)
{
  const sensors::LaserScan s = cast(test::door(2.0, 0.55), geometry::Pose2(0.3, 0, 0));
  EXPECT_TRUE(detect_narrow_passages(s, NarrowPassageOptions{}).empty());
}

TEST(NarrowPassage, TooFarAway)
{
  NarrowPassageOptions o;
  o.max_distance = 2.5;
  EXPECT_TRUE(detect_narrow_passages(cast(test::door(4.0, 0.9), geometry::Pose2()), o).empty());
  EXPECT_EQ(detect_narrow_passages(cast(test::door(2.0, 0.9), geometry::Pose2()), o).size(), 1u);
}

TEST(NarrowPassage, NicheWithoutFreeSpaceBehindIsInvalid)
{
  // A 0.9 m wide niche only 0.2 m deep: no free space behind the passage line (fig. 4.11).
  test::Walls ws = {{{2, 0.45}, {2, 4}}, {{2, -4}, {2, -0.45}}, {{2.2, -0.45}, {2.2, 0.45}},
                    {{2, 0.45}, {2.2, 0.45}}, {{2, -0.45}, {2.2, -0.45}}};
  EXPECT_TRUE(detect_narrow_passages(cast(ws, geometry::Pose2()), NarrowPassageOptions{}).empty());
}

TEST(NarrowPassage, WalkFindsTheOpeningBehindAProtrudingFrame)
{
  // The closest left point is a post nearer to the robot; the walk along the wall behind it
  // leads to the real edge of the opening, an additional candidate (fig. 4.10).
  const NarrowPassageOptions o;
  test::Walls ws = test::door(2.0, 1.6);
  ws.push_back({{1.6, 0.8}, {2.0, 0.8}});   // left jamb wall returning toward the robot
  ws.push_back({{2.0, 0.4}, {2.0, 0.8}});   // a short wall continuing the jamb into the gap
  const sensors::LaserScan s = cast(ws, geometry::Pose2());
  const auto nps = detect_narrow_passages(s, o);
  ASSERT_EQ(nps.size(), 1u);
  EXPECT_NEAR(nps[0].left.y(), 0.4, 0.06);   // the edge where free space starts
  EXPECT_NEAR(nps[0].right.y(), -0.8, 0.06);
}

TEST(NarrowPassage, WidthOutsideTheDoorRangeIsNoDoor)
{
  EXPECT_TRUE(detect_narrow_passages(cast(test::door(2.0, 1.8), geometry::Pose2()), NarrowPassageOptions{}).empty());
}

TEST(NarrowPassage, ShippedConfigsTakeTheBuildingsWiderDoorways)
{
  // The door-width range comes from the environment (diss. 4.2.1). A 1.4 m doorway, as 21 of the
  // IPA buildings' 277 are (1.3-1.5 m), is no passage with the dissertation's 0.7-1.3 m; the
  // shipped configs take it, and still not a 1.8 m opening.
  const sensors::LaserScan wide_door = cast(test::door(2.0, 1.4), geometry::Pose2(0.3, 0.05, 0.0), 0.005);
  EXPECT_TRUE(detect_narrow_passages(wide_door, NarrowPassageOptions{}).empty());
  for (const char* name : {"gateway_detector.yaml", "gateway_detector_aligned.yaml"}) {
    const auto o = load_detector_options(config::Config::load(std::string(RGNAV_SOURCE_DIR "/config/") + name),
                                         config::load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml"));
    const auto nps = detect_narrow_passages(wide_door, o.narrow_passages);
    ASSERT_EQ(nps.size(), 1u) << name;
    EXPECT_NEAR(nps[0].width, 1.4, 0.1) << name;
    EXPECT_TRUE(detect_narrow_passages(cast(test::door(2.0, 1.8), geometry::Pose2()), o.narrow_passages).empty()) << name;
  }
}

}  // namespace
}  // namespace rgnav::gateway_detector
