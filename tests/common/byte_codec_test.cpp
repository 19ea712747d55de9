// The shared byte codec (persist/byte_codec.h) of the scan mapper's and the RG kernel's
// persisted state: exact round trips, and damaged bytes refused with CorruptBytes, never read.
#include "persist/byte_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rgnav::persist {
namespace {

TEST(ByteCodec, RoundTripIsBitExact)
{
  ByteWriter w;
  const double third = 1.0 / 3.0;
  Eigen::Matrix3d m;
  m << 1, 2, 3, 4, 5, 6, 7, 8, third;
  w.put(int64_t{-42});
  w.put(third);
  w.put(Eigen::Vector2d(0.1, -2e-300));
  w.put(geometry::Pose2(1.5, -2.25, 0.7));
  w.put(m);
  w.put(std::string("region\0name", 11));
  w.put_points({{1, 2}, {3, 4}});
  const std::string bytes = w.take();

  ByteReader r(bytes);
  EXPECT_EQ(r.get<int64_t>(), -42);
  EXPECT_EQ(r.finite(), third);   // bit for bit, not to a tolerance
  EXPECT_EQ(r.vec(), Eigen::Vector2d(0.1, -2e-300));
  const geometry::Pose2 p = r.pose();
  EXPECT_EQ(p.x(), 1.5);
  EXPECT_EQ(p.y(), -2.25);
  EXPECT_EQ(p.theta(), geometry::Pose2(1.5, -2.25, 0.7).theta());
  EXPECT_EQ(r.matrix(), m);
  EXPECT_EQ(r.str(), std::string("region\0name", 11));
  const auto pts = r.points();
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[1], Eigen::Vector2d(3, 4));
  EXPECT_TRUE(r.at_end());
}

TEST(ByteCodec, TruncatedBytesAreRefusedAtEveryLength)
{
  ByteWriter w;
  w.put(geometry::Pose2(1, 2, 0.3));
  w.put_points({{1, 2}, {3, 4}, {5, 6}});
  const std::string bytes = w.bytes();
  for (size_t n = 0; n < bytes.size(); ++n) {
    const std::string cut = bytes.substr(0, n);
    ByteReader r(cut);
    EXPECT_THROW(
        {
          r.pose();
          r.points();
        },
        CorruptBytes)
        << "cut at " << n;
  }
}

TEST(ByteCodec, CountsBeyondTheDataOrTheCallersBoundAreRefused)
{
  ByteWriter w;
  w.put(uint64_t{1'000'000'000'000});   // a flipped high bit: would allocate terabytes
  w.put(1.0);
  {
    ByteReader r(w.bytes());
    EXPECT_THROW(r.points(), CorruptBytes);
  }
  ByteWriter small;
  small.put(uint64_t{3});
  small.put(std::string("abcdef"));
  ByteReader r(small.bytes());
  EXPECT_THROW(r.count(1, 2), CorruptBytes);   // within the data, above the caller's bound
  ByteReader ok(small.bytes());
  EXPECT_EQ(ok.count(1, 3), 3u);
}

TEST(ByteCodec, NonFiniteNumbersAreRefusedWhereFiniteOnesAreAskedFor)
{
  ByteWriter w;
  w.put(std::numeric_limits<double>::quiet_NaN());
  w.put(std::numeric_limits<double>::infinity());
  ByteReader r(w.bytes());
  EXPECT_THROW(r.finite(), CorruptBytes);
  EXPECT_TRUE(std::isinf(r.get<double>()));   // a raw get is the caller's business
}

}  // namespace
}  // namespace rgnav::persist
