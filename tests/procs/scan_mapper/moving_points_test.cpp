// The seen-through test that leaves points on things that moved out of registration. Its effect
// on mapping is measured by the SLAM bench's office_people world (people walking in hallways).
#include <gtest/gtest.h>

#include "scan_mapper/moving_points.h"
#include "synthetic_world.h"

namespace sm = rgnav::scan_mapper;
using sm::testing::Segment;

namespace {

// Square room 10 x 10 m around the origin.
std::vector<Segment> room()
{
  return {{{-5, -5}, {5, -5}}, {{5, -5}, {5, 5}}, {{5, 5}, {-5, 5}}, {{-5, 5}, {-5, -5}}};
}

}  // namespace

TEST(ScanView, SeesThroughWhereBothBeamsReachPastByTheMargin)
{
  const auto world = room();
  const sm::testing::LaserModel m;
  const rgnav::sensors::LaserScan scan = sm::testing::cast_scan(world, sm::Pose2{}, m);
  sm::MovingPointOptions o;
  o.margin_m = 0.3;
  const sm::ScanView view(scan, sm::Pose2{}, o);
  const Eigen::Vector2d none = Eigen::Vector2d::Zero();
  EXPECT_TRUE(view.sees_through({3.0, 0.5}, none));    // free space in front of the wall
  EXPECT_FALSE(view.sees_through({4.9, 0.5}, none));   // within the margin of the wall
  EXPECT_FALSE(view.sees_through({5.5, 0.5}, none));   // behind it
  EXPECT_FALSE(view.sees_through({-3.0, 0.5}, none));  // behind the laser: not in its field of view
  // A surface seen at a flat angle is not tested: a small pose error slides the beam along it.
  EXPECT_TRUE(view.sees_through({3.0, 0.5}, {1.0, 0.0}));
  EXPECT_FALSE(view.sees_through({3.0, 0.5}, {0.0, 1.0}));
  o.margin_m = 2.5;  // only beams reaching 2.5 m past the point count
  const sm::ScanView strict(scan, sm::Pose2{}, o);
  EXPECT_FALSE(strict.sees_through({3.0, 0.5}, none));
}

TEST(ScanView, ABeamWithoutReturnSeesThroughToTheRangeLimit)
{
  sm::testing::LaserModel m;
  m.max_range = 8.0;
  const rgnav::sensors::LaserScan scan = sm::testing::cast_scan({}, sm::Pose2{}, m);  // nothing within range
  const sm::ScanView view(scan, sm::Pose2{1.0, 0.0, 0.0}, sm::MovingPointOptions{});
  EXPECT_TRUE(view.sees_through({6.0, 0.0}, Eigen::Vector2d::Zero()));
  EXPECT_FALSE(view.sees_through({8.9, 0.0}, Eigen::Vector2d::Zero()));
}

TEST(ScanView, MarksOnlyWhatAViewSeesThrough)
{
  const rgnav::sensors::LaserScan scan = sm::testing::cast_scan(room(), sm::Pose2{}, sm::testing::LaserModel{});
  const std::vector<sm::ScanView> views{sm::ScanView(scan, sm::Pose2{}, sm::MovingPointOptions{})};
  const sm::Points points{{3.0, 0.5}, {5.0, 0.5}, {2.0, -1.0}};
  const sm::Points normals(points.size(), Eigen::Vector2d(1.0, 0.0));
  std::vector<char> keep;
  mark_seen_through(views, points, normals, {1, 1, 0}, &keep);
  EXPECT_EQ(keep, (std::vector<char>{0, 1, 0}));  // the wall point stays
}
