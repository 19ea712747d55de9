#include "restart_policy.h"

#include <gtest/gtest.h>

namespace rgnav::supervisor {
namespace {

using std::chrono::milliseconds;

TEST(RestartPolicy, BacksOffExponentiallyThenGivesUp)
{
  RestartOptions o;
  o.initial_backoff = milliseconds(100);
  o.max_backoff = milliseconds(300);
  o.max_restarts = 4;
  o.window = milliseconds(10000);
  RestartPolicy p(o);
  const auto t = RestartPolicy::Clock::time_point{} + std::chrono::hours(1);
  EXPECT_EQ(p.on_failure(t, t).delay, milliseconds(100));
  EXPECT_EQ(p.on_failure(t + milliseconds(200), t + milliseconds(150)).delay, milliseconds(200));
  EXPECT_EQ(p.on_failure(t + milliseconds(500), t + milliseconds(450)).delay, milliseconds(300));  // capped
  EXPECT_EQ(p.on_failure(t + milliseconds(900), t + milliseconds(850)).delay, milliseconds(300));
  EXPECT_TRUE(p.on_failure(t + milliseconds(1300), t + milliseconds(1250)).give_up);
}

TEST(RestartPolicy, OldRestartsLeaveTheWindowAndStableRunsResetTheBackoff)
{
  RestartOptions o;
  o.initial_backoff = milliseconds(100);
  o.max_restarts = 2;
  o.window = milliseconds(1000);
  o.stable_after = milliseconds(5000);
  RestartPolicy p(o);
  const auto t = RestartPolicy::Clock::time_point{} + std::chrono::hours(1);
  p.on_failure(t, t);
  p.on_failure(t + milliseconds(100), t + milliseconds(50));
  EXPECT_EQ(p.restarts_in_window(t + milliseconds(200)), 2);
  // 2 s later both restarts are out of the window; the process had not run stably yet.
  const auto d = p.on_failure(t + milliseconds(2000), t + milliseconds(1900));
  EXPECT_FALSE(d.give_up);
  EXPECT_EQ(d.delay, milliseconds(400));
  // After a long stable run the back-off starts again from the beginning.
  EXPECT_EQ(p.on_failure(t + milliseconds(9000), t + milliseconds(2100)).delay, milliseconds(100));
  p.reset();
  EXPECT_EQ(p.restarts_in_window(t + milliseconds(9000)), 0);
}

}  // namespace
}  // namespace rgnav::supervisor
