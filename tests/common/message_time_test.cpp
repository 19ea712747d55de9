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

// One input stamped far ahead (a corrupted copy) does not move the clock: taken, it would hold
// every message-time timer and age every input for as long as it is ahead. A second input near
// it confirms a real jump (a log replay skipping, a sender back after a long gap).
TEST(MessageClock, AStampFarAheadWaitsForASecondToConfirmIt)
{
  MessageClock c(Duration(1'000'000), Duration(250'000));
  const int64_t t0 = 1'700'000'000'000'000;
  EXPECT_TRUE(c.observe(from_utime(t0)));
  EXPECT_FALSE(c.observe(from_utime(t0 + 600'000'000)));
  EXPECT_EQ(to_utime(c.now()), t0);
  EXPECT_TRUE(c.observe(from_utime(t0 + 900'000)));   // within the bound: taken
  EXPECT_FALSE(c.observe(from_utime(t0 + 600'000'000)));
  EXPECT_FALSE(c.observe(from_utime(t0 + 900'000'000)));  // far from the held one: held instead
  EXPECT_TRUE(c.observe(from_utime(t0 + 900'100'000)));   // confirmed
  EXPECT_EQ(to_utime(c.now()), t0 + 900'100'000);
}

TEST(MessageTime, UtimeRoundTrip)
{
  EXPECT_EQ(to_utime(from_utime(1'700'000'000'123'456)), 1'700'000'000'123'456);
  EXPECT_DOUBLE_EQ(to_seconds(Duration(1'500'000)), 1.5);
}

}  // namespace
}  // namespace rgnav::time
