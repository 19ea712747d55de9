#include <gtest/gtest.h>

#include <cmath>

#include "sensors/laser_scan.h"

namespace rgnav::sensors {
namespace {

LaserScan three_beams()
{
  LaserScan s;
  s.angle_min = -M_PI / 2;
  s.angle_increment = M_PI / 2;
  s.range_min = 0.1;
  s.range_max = 8.0;
  s.ranges = {2.f, 8.f, 0.f};
  return s;
}

TEST(LaserScan, BeamsAreRaysCounterClockwiseFromAngleMin)
{
  const LaserScan s = three_beams();
  EXPECT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s.bearing(1), 0.0);
  EXPECT_NEAR(s.point(0).x(), 0.0, 1e-12);
  EXPECT_NEAR(s.point(0).y(), -2.0, 1e-12);
  EXPECT_NEAR(s.direction(2).y(), 1.0, 1e-12);
}

TEST(LaserScan, ReadingsAreHitsNoReturnsOrInvalid)
{
  const LaserScan s = three_beams();
  EXPECT_TRUE(s.hit(0));
  EXPECT_TRUE(s.no_return(1));
  EXPECT_FALSE(s.hit(1));
  EXPECT_TRUE(s.invalid(2));
  EXPECT_FALSE(s.invalid(0));
}

TEST(LaserScan, IndexOfIsTheNearestBeamWithinTheFieldOfView)
{
  const LaserScan s = three_beams();
  EXPECT_EQ(s.index_of(0.1), 1u);
  EXPECT_EQ(s.index_of(M_PI), 2u);
  EXPECT_EQ(s.index_of(-M_PI), 0u);
  EXPECT_EQ(LaserScan{}.index_of(0.0), 0u);
}

TEST(LaserScan, MessagePrecisionRoundsTheHeaderOnly)
{
  LaserScan s = three_beams();
  s.range_max = 8.183;
  const LaserScan r = with_message_precision(s);
  EXPECT_EQ(r.range_max, static_cast<double>(8.183f));
  EXPECT_EQ(r.angle_min, static_cast<double>(static_cast<float>(-M_PI / 2)));
  EXPECT_EQ(r.ranges, s.ranges);
}

}  // namespace
}  // namespace rgnav::sensors
