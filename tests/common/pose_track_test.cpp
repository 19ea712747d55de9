#include <gtest/gtest.h>

#include "geometry/pose_track.h"

namespace rgnav::geometry {
namespace {

TEST(PoseInterpolation, ShortestWayRoundInTheta)
{
  const Pose2 p = interpolate(Pose2(0, 0, 3.0), Pose2(2, 4, -3.0), 0.5);
  EXPECT_DOUBLE_EQ(p.x(), 1.0);
  EXPECT_DOUBLE_EQ(p.y(), 2.0);
  EXPECT_NEAR(std::fabs(p.theta()), M_PI, 1e-12);   // through pi, not through 0
}

TEST(PoseTrack, SampleInterpolatedOrLast)
{
  PoseTrack track;
  EXPECT_FALSE(track.at(0));
  EXPECT_FALSE(track.clamped_at(0));
  track.add(100, Pose2(0, 0, 0));
  track.add(200, Pose2(1, 0, 0.2));
  track.add(300, Pose2(1, 2, 0.4));
  EXPECT_FALSE(track.at(99));                        // before the first sample
  EXPECT_DOUBLE_EQ(track.clamped_at(99)->x(), 0.0);  // ... or the first one
  EXPECT_DOUBLE_EQ(track.at(200)->theta(), 0.2);     // a sample's own time
  const Pose2 mid = *track.at(250);
  EXPECT_DOUBLE_EQ(mid.x(), 1.0);
  EXPECT_DOUBLE_EQ(mid.y(), 1.0);
  EXPECT_DOUBLE_EQ(mid.theta(), 0.2 + 0.5 * (0.4 - 0.2));
  EXPECT_DOUBLE_EQ(track.at(1000)->y(), 2.0);        // after the last: the last
  EXPECT_DOUBLE_EQ(track.clamped_at(1000)->y(), 2.0);
}

TEST(PoseTrack, OfTwoSamplesAtOneTimeTheLaterCounts)
{
  PoseTrack track;
  track.add(100, Pose2(0, 0, 0));
  track.add(100, Pose2(5, 0, 0));
  track.add(200, Pose2(7, 0, 0));
  EXPECT_DOUBLE_EQ(track.at(100)->x(), 5.0);
  EXPECT_DOUBLE_EQ(track.at(150)->x(), 6.0);
}

}  // namespace
}  // namespace rgnav::geometry
