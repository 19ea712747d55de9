#include <gtest/gtest.h>

#include <cmath>

#include "geometry/segment2.h"

namespace rgnav::geometry {
namespace {

using V = Eigen::Vector2d;

TEST(Segment2, CrossIsCounterClockwisePositive)
{
  EXPECT_EQ(cross(V(1, 0), V(0, 1)), 1.0);
  EXPECT_EQ(cross(V(0, 1), V(1, 0)), -1.0);
  EXPECT_EQ(cross(V(2, 2), V(1, 1)), 0.0);
}

TEST(Segment2, RayMeetsLineAheadBehindAndBeyondTheEnds)
{
  // The ray along +x from the origin, the line x = 3 from y = -1 to y = 1.
  const auto ahead = ray_meets_line(V(0, 0), V(1, 0), V(3, -1), V(3, 1), 1e-12);
  ASSERT_TRUE(ahead);
  EXPECT_DOUBLE_EQ(ahead->along_ray, 3.0);
  EXPECT_DOUBLE_EQ(ahead->along_line, 0.5);
  const auto behind = ray_meets_line(V(5, 0), V(1, 0), V(3, -1), V(3, 1), 1e-12);
  ASSERT_TRUE(behind);
  EXPECT_DOUBLE_EQ(behind->along_ray, -2.0);
  // The line is infinite: past b the hit is still reported, with along_line > 1.
  const auto past = ray_meets_line(V(0, 3), V(1, 0), V(3, -1), V(3, 1), 1e-12);
  ASSERT_TRUE(past);
  EXPECT_DOUBLE_EQ(past->along_line, 2.0);
  // along_ray is in units of |dir|.
  EXPECT_DOUBLE_EQ(ray_meets_line(V(0, 0), V(2, 0), V(3, -1), V(3, 1), 0.0)->along_ray, 1.5);
}

TEST(Segment2, RayMeetsLineParallelIsTheCallersTolerance)
{
  EXPECT_FALSE(ray_meets_line(V(0, 0), V(1, 0), V(0, 1), V(5, 1), 1e-12));
  // |cross| = 1e-10: parallel for a 1e-9 tolerance, not for 1e-12.
  const V dir(1, 0), a(0, 1), b(1, 1e-10 + 1);
  const double denom = std::fabs(cross(dir, b - a));
  EXPECT_FALSE(ray_meets_line(V(0, 0), dir, a, b, 1e-9));
  EXPECT_TRUE(ray_meets_line(V(0, 0), dir, a, b, 1e-12));
  // The comparison is strict: |cross| equal to the tolerance is not parallel.
  EXPECT_TRUE(ray_meets_line(V(0, 0), dir, a, b, denom));
  EXPECT_FALSE(ray_meets_line(V(0, 0), dir, a, b, std::nextafter(denom, 1.0)));
  // A zero tolerance still meets an exactly parallel line (in an infinity or NaN): callers
  // that pass 0 know the lines cross.
  EXPECT_TRUE(ray_meets_line(V(0, 0), V(1, 0), V(0, 1), V(5, 1), 0.0));
}

TEST(Segment2, SegmentsCrossOnlyProperly)
{
  EXPECT_TRUE(segments_cross(V(0, 0), V(2, 2), V(0, 2), V(2, 0)));
  EXPECT_FALSE(segments_cross(V(0, 0), V(1, 1), V(3, 0), V(0, 3)));    // would cross if longer
  EXPECT_FALSE(segments_cross(V(0, 0), V(2, 0), V(1, 0), V(1, 1)));    // touches at an end
  EXPECT_FALSE(segments_cross(V(0, 0), V(2, 0), V(1, 0), V(3, 0)));    // collinear overlap
  EXPECT_FALSE(segments_cross(V(0, 0), V(2, 0), V(0, 1), V(2, 1)));    // parallel
  EXPECT_TRUE(segments_cross(V(2, 2), V(0, 0), V(2, 0), V(0, 2)));     // either direction
}

TEST(Segment2, PointSegmentDistanceInsideAndBeyondTheEnds)
{
  EXPECT_DOUBLE_EQ(point_segment_distance(V(1, 2), V(0, 0), V(4, 0)), 2.0);
  EXPECT_DOUBLE_EQ(point_segment_distance(V(-3, 4), V(0, 0), V(4, 0)), 5.0);
  EXPECT_DOUBLE_EQ(point_segment_distance(V(7, -4), V(0, 0), V(4, 0)), 5.0);
  EXPECT_DOUBLE_EQ(point_segment_distance(V(2, 0), V(0, 0), V(4, 0)), 0.0);
}

TEST(Segment2, PointSegmentDistanceDegenerateSegmentIsTheCallersTolerance)
{
  // A zero-length segment is its point by default.
  EXPECT_DOUBLE_EQ(point_segment_distance(V(3, 4), V(0, 0), V(0, 0)), 5.0);
  // A 1e-10 m segment is a segment by default, the point a for a 1e-18 m^2 tolerance.
  const V a(0, 0), b(1e-10, 0), p(1e-10, 1e-10);
  EXPECT_DOUBLE_EQ(point_segment_distance(p, a, b), 1e-10);
  EXPECT_DOUBLE_EQ(point_segment_distance(p, a, b, 1e-18), std::sqrt(2.0) * 1e-10);
}

}  // namespace
}  // namespace rgnav::geometry
