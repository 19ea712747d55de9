#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "msg/conversions.h"
#include "sample_messages.h"

namespace rgnav::msg {
namespace {

std::vector<uint8_t> encoded(const laser_scan_t& m)
{
  std::vector<uint8_t> raw(static_cast<size_t>(m.getEncodedSize()));
  m.encode(raw.data(), 0, static_cast<int>(raw.size()));
  return raw;
}

TEST(LaserScanConversions, MessageRoundTripIsExact)
{
  const laser_scan_t m = rgnav::testing::sample_laser_scan(7, 181, /*variant without intensities*/ 0);
  ASSERT_EQ(m.nintensities, 0);
  const sensors::LaserScan s = to_laser_scan(m);
  EXPECT_EQ(s.utime, m.utime);
  EXPECT_EQ(s.scan_id, 7);
  EXPECT_EQ(s.sensor, "laser_front");
  EXPECT_EQ(s.angle_min, static_cast<double>(m.angle_min));
  EXPECT_EQ(s.angle_increment, static_cast<double>(m.angle_increment));
  EXPECT_EQ(s.range_min, static_cast<double>(m.range_min));
  EXPECT_EQ(s.range_max, static_cast<double>(m.range_max));
  EXPECT_EQ(s.scan_time, static_cast<double>(m.scan_time));
  EXPECT_EQ(s.ranges, m.ranges);
  EXPECT_EQ(encoded(to_msg(s)), encoded(m));
}

// A scan as the simulator makes it: the header in double, the ranges in float.
sensors::LaserScan simulated_scan()
{
  std::vector<float> ranges;
  for (int i = 0; i < 181; ++i) ranges.push_back(0.5f + 0.01f * static_cast<float>(i));
  return {123, 7, "x", -M_PI / 2, M_PI / 180, 0.001, 8.183, 1.0 / 75, ranges};
}

TEST(LaserScanConversions, ScanWithFloatHeaderRoundTripsExactly)
{
  const sensors::LaserScan s = sensors::with_message_precision(simulated_scan());
  const sensors::LaserScan back = to_laser_scan(to_msg(s));
  EXPECT_EQ(back.utime, 123);
  EXPECT_EQ(back.scan_id, 7);
  EXPECT_EQ(back.sensor, "x");
  EXPECT_EQ(back.angle_min, s.angle_min);
  EXPECT_EQ(back.angle_increment, s.angle_increment);
  EXPECT_EQ(back.range_min, s.range_min);
  EXPECT_EQ(back.range_max, s.range_max);
  EXPECT_EQ(back.scan_time, s.scan_time);
  ASSERT_EQ(back.size(), s.size());
  EXPECT_EQ(back.ranges, s.ranges);
}

TEST(LaserScanConversions, DoubleHeaderIsRoundedToFloatAsOnTheBus)
{
  const sensors::LaserScan s = simulated_scan();
  const sensors::LaserScan back = to_laser_scan(to_msg(s));
  const sensors::LaserScan rounded = sensors::with_message_precision(s);
  EXPECT_EQ(back.angle_min, static_cast<double>(static_cast<float>(-M_PI / 2)));
  EXPECT_EQ(back.angle_min, rounded.angle_min);
  EXPECT_EQ(back.angle_increment, rounded.angle_increment);
  EXPECT_EQ(back.range_min, rounded.range_min);
  EXPECT_EQ(back.range_max, rounded.range_max);
  EXPECT_EQ(back.scan_time, rounded.scan_time);
  EXPECT_NE(back.range_max, s.range_max);  // 8.183 is no float
  EXPECT_EQ(back.ranges, s.ranges);
}

TEST(LaserScanConversions, IntensitiesAreNotKept)
{
  const laser_scan_t m = rgnav::testing::sample_laser_scan(1, 181, /*variant with intensities*/ 1);
  ASSERT_EQ(m.nintensities, 181);
  const laser_scan_t back = to_msg(to_laser_scan(m));
  EXPECT_EQ(back.nintensities, 0);
  EXPECT_TRUE(back.intensities.empty());
  EXPECT_EQ(back.ranges, m.ranges);
}

TEST(PoseConversions, RoundTripAndNormalisedAngle)
{
  const geometry::Pose2 p(1.5, -2.0, 0.75);
  const geometry::Pose2 back = to_pose2(to_msg(p));
  EXPECT_EQ(back.x(), 1.5);
  EXPECT_EQ(back.y(), -2.0);
  EXPECT_EQ(back.theta(), 0.75);
  pose2d_t m;
  m.x = 0;
  m.y = 0;
  m.theta = 3 * M_PI / 2;  // senders need not normalise: the pose does
  EXPECT_NEAR(to_pose2(m).theta(), -M_PI / 2, 1e-12);
  EXPECT_NEAR(to_msg(to_pose2(m)).theta, -M_PI / 2, 1e-12);
}

}  // namespace
}  // namespace rgnav::msg
