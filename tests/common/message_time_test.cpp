#include "time/message_time.h"

#include <gtest/gtest.h>

namespace rgnav::time {
namespace {

TEST(MessageClock, NeverGoesBackwards)
{
  MessageClock c;
  EXPECT_FALSE(c.has_time());
  EXPECT_TRUE(c.observe(from_utime(1000)));
  EXPECT_FALSE(c.observe(from_utime(999)));
  EXPECT_FALSE(c.observe(from_utime(1000)));
  EXPECT_EQ(to_utime(c.now()), 1000);
  EXPECT_TRUE(c.observe(from_utime(2000)));
  EXPECT_EQ(to_utime(c.now()), 2000);
  c.reset();
  EXPECT_TRUE(c.observe(from_utime(5)));
}

TEST(MessageTime, UtimeRoundTrip)
{
  EXPECT_EQ(to_utime(from_utime(1'700'000'000'123'456)), 1'700'000'000'123'456);
  EXPECT_DOUBLE_EQ(to_seconds(Duration(1'500'000)), 1.5);
}

}  // namespace
}  // namespace rgnav::time
