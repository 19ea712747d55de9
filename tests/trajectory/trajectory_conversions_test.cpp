#include "trajectory/trajectory_conversions.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bus/typed.h"

namespace rgnav::trajectory {
namespace {

void expect_same(const Segment& a, const Segment& b)
{
  EXPECT_EQ(a.kind(), b.kind());
  EXPECT_DOUBLE_EQ(a.length(), b.length());
  EXPECT_DOUBLE_EQ(a.kappa0(), b.kappa0());
  EXPECT_DOUBLE_EQ(a.kappa1(), b.kappa1());
  EXPECT_DOUBLE_EQ(a.turn_angle(), b.turn_angle());
  EXPECT_DOUBLE_EQ(a.start().x(), b.start().x());
  EXPECT_DOUBLE_EQ(a.start().theta(), b.start().theta());
  for (double s : {0.0, 0.3 * a.length(), a.length()}) {
    EXPECT_NEAR((a.pose_at(s).translation() - b.pose_at(s).translation()).norm(), 0.0, 1e-12);
  }
  EXPECT_NEAR(geometry::normalize_angle(a.end().theta() - b.end().theta()), 0.0, 1e-12);
}

TEST(TrajectoryConversions, SegmentRoundTrip)
{
  const Pose2 p(1.25, -0.5, 2.9);
  Segment arc = Segment::arc(p, -0.7, 1.3);
  arc.set_v_max(0.4);
  for (const Segment& s : {Segment::line(p, 2.0), arc, Segment::clothoid(p, 0.1, -1.2, 0.9),
                           Segment::conic(p, 1.5, 0.6, 0.4, false, 1.1), Segment::turn(p, -2.2)}) {
    const trajectory_segment_t m = to_msg(s, 0.25, 0.6);
    std::string why;
    const auto back = from_msg(m, &why);
    ASSERT_TRUE(back) << why;
    expect_same(s, *back);
    EXPECT_DOUBLE_EQ(m.v_end, 0.25);
  }
  EXPECT_DOUBLE_EQ(to_msg(arc, 0, 0.6).v_max, 0.4);
  EXPECT_DOUBLE_EQ(to_msg(Segment::line(p, 1), 0, 0.6).v_max, 0.6);
}

TEST(TrajectoryConversions, TrajectoryRoundTripOverTheWire)
{
  Trajectory t;
  t.id = 42;
  t.stamp = time::from_utime(1'000'000);
  t.chain.push_back(Segment::line(Pose2(0, 0, 0), 1.0));
  t.chain.append_at_end(Segment::clothoid(Pose2(), 0.0, 1.0, 0.5));
  t.chain.append_at_end(Segment::turn(Pose2(), 0.3));
  t.predicted_end = time::from_utime(5'000'000);
  Limits lim;
  const VelocityProfile prof = VelocityProfile::compute(t.chain, lim, 0.0, 0.0);
  const trajectory_t m = to_msg(t, &prof, 0.6);
  std::vector<uint8_t> buf;
  std::string why;
  ASSERT_TRUE(bus::encode(m, &buf, &why)) << why;
  trajectory_t decoded;
  ASSERT_TRUE(bus::decode(buf.data(), buf.size(), &decoded, &why)) << why;
  const auto back = from_msg(decoded, &why);
  ASSERT_TRUE(back) << why;
  EXPECT_EQ(back->id, 42);
  EXPECT_EQ(back->stamp, t.stamp);
  EXPECT_EQ(back->predicted_end, t.predicted_end);
  ASSERT_EQ(back->chain.size(), 3u);
  for (size_t i = 0; i < 3; ++i) expect_same(t.chain[i], back->chain[i]);
  EXPECT_DOUBLE_EQ(decoded.segments[0].v_end, prof.segment_end_speed(0));
}

TEST(TrajectoryConversions, RefusesNonsense)
{
  trajectory_segment_t m = to_msg(Segment::line(Pose2(), 1.0), 0, 0.5);
  std::string why;
  m.kind = 9;
  EXPECT_FALSE(from_msg(m, &why));
  EXPECT_NE(why.find("kind"), std::string::npos);
  m = to_msg(Segment::conic(Pose2(), 1, 1, 0, true, 1), 0, 0.5);
  m.param[1] = 0.0;
  EXPECT_FALSE(from_msg(m, &why));
  m = to_msg(Segment::line(Pose2(), 1.0), 0, 0.5);
  m.length = 1e6;
  EXPECT_FALSE(from_msg(m, &why));
}

}  // namespace
}  // namespace rgnav::trajectory
