// LoopTimeline on synthetic times: deadlines, overruns, and the stall account that tells a
// step that ran long (the loop's own work) from a late wake (scheduler or machine).
#include "lld/loop_timeline.h"

#include <gtest/gtest.h>

#include "lld/loop_stats_json.h"

namespace rgnav::lld {
namespace {

constexpr int64_t kMs = 1'000'000;

// Runs `n` regular ticks of a 50 ms loop from last_wake: each step takes 1 ms, each wake
// comes 0.1 ms after its deadline. Returns the time of the last wake.
int64_t regular_ticks(LoopTimeline& tl, int n, int64_t last_wake)
{
  for (int i = 0; i < n; ++i) {
    const int64_t deadline = tl.next_deadline_ns();
    tl.tick(last_wake + 1 * kMs, deadline + kMs / 10, StepUsage{});
    last_wake = deadline + kMs / 10;
  }
  return last_wake;
}

TEST(LoopTimeline, RegularTicksHaveNoStalls)
{
  LoopTimeline tl(std::chrono::milliseconds(50));
  tl.start(0);
  EXPECT_EQ(tl.next_deadline_ns(), 50 * kMs);
  regular_ticks(tl, 20, 0);
  const LoopStats s = tl.stats();
  EXPECT_EQ(s.ticks, 20);
  EXPECT_EQ(s.overruns, 0);
  EXPECT_TRUE(s.stalls.empty());
  EXPECT_EQ(s.long_steps + s.late_wakes, 0);
  EXPECT_NEAR(s.step_max_ms, 1.0, 0.2);  // wake to the end of the step
  EXPECT_LT(s.jitter_max_ms, 0.2);
}

TEST(LoopTimeline, LateWakeAfterAShortStepIsNotTheLoopsFault)
{
  LoopTimeline tl(std::chrono::milliseconds(50), 5.0);
  tl.start(0);
  int64_t wake = regular_ticks(tl, 5, 0);
  // The step ends after 1 ms, but the thread gets the CPU 30 ms after the deadline.
  const int64_t deadline = tl.next_deadline_ns();
  const auto t = tl.tick(wake + kMs, deadline + 30 * kMs, StepUsage{0, 0, 1});
  EXPECT_EQ(t.missed, 0);
  EXPECT_NEAR(t.jitter_ms, 29.9, 1e-6);
  // The next tick is on time again: its short period is jitter, not another stall.
  const int64_t d2 = tl.next_deadline_ns();
  EXPECT_EQ(d2, deadline + 50 * kMs);  // absolute deadlines: no drift from the late wake
  tl.tick(deadline + 31 * kMs, d2, StepUsage{});
  const LoopStats s = tl.stats();
  ASSERT_EQ(s.stalls.size(), 1u);
  EXPECT_EQ(s.late_wakes, 1);
  EXPECT_EQ(s.long_steps, 0);
  EXPECT_FALSE(s.stalls[0].step_overran);
  EXPECT_NEAR(s.stalls[0].late_ms, 30.0, 1e-6);
  EXPECT_NEAR(s.stalls[0].step_ms, 1.0, 1e-6);
  EXPECT_EQ(s.stalls[0].wake_ns, deadline + 30 * kMs);
  EXPECT_EQ(s.stalls[0].usage.involuntary_switches, 1);
}

TEST(LoopTimeline, LongStepIsTheLoopsOwnAndCountsOverruns)
{
  LoopTimeline tl(std::chrono::milliseconds(50), 5.0);
  tl.start(0);
  int64_t wake = regular_ticks(tl, 5, 0);
  // The step blocks for 120 ms: this tick's deadline and the one after pass while it runs;
  // the tick runs late, the one after is skipped.
  const int64_t deadline = tl.next_deadline_ns();
  const int64_t end = wake + 120 * kMs;
  const auto t = tl.tick(end, end + kMs / 10, StepUsage{3, 0, 0});
  EXPECT_EQ(t.missed, 1);
  EXPECT_GT(tl.next_deadline_ns(), end);
  EXPECT_EQ((tl.next_deadline_ns() - deadline) % (50 * kMs), 0);
  const LoopStats s = tl.stats();
  EXPECT_EQ(s.overruns, 1);
  ASSERT_EQ(s.stalls.size(), 1u);
  EXPECT_TRUE(s.stalls[0].step_overran);
  EXPECT_EQ(s.long_steps, 1);
  EXPECT_EQ(s.late_wakes, 0);
  EXPECT_NEAR(s.stalls[0].step_ms, 120.0, 1e-6);
  EXPECT_EQ(s.stalls[0].usage.minor_faults, 3);
  EXPECT_NEAR(s.step_max_ms, 120.0, 1e-6);
}

TEST(LoopTimeline, KeepsTheWorstStallsFirstAndSumsUsageAfterWarmup)
{
  LoopTimeline tl(std::chrono::milliseconds(10), 1.0, /*max_stalls=*/3, /*warmup_ticks=*/2);
  tl.start(0);
  int64_t wake = 0;
  const double lates[] = {2.0, 8.0, 4.0, 6.0, 3.0};
  for (double late : lates) {
    const int64_t deadline = tl.next_deadline_ns();
    const int64_t w = deadline + static_cast<int64_t>(late * kMs);
    tl.tick(wake + kMs / 2, w, StepUsage{1, 0, 0});
    wake = w;
  }
  const LoopStats s = tl.stats();
  ASSERT_EQ(s.stalls.size(), 3u);
  EXPECT_NEAR(s.stalls[0].late_ms, 8.0, 1e-6);
  EXPECT_NEAR(s.stalls[1].late_ms, 6.0, 1e-6);
  EXPECT_NEAR(s.stalls[2].late_ms, 4.0, 1e-6);
  EXPECT_EQ(s.late_wakes, 4);  // every late wake is counted, kept or not (the first tick is not measured)
  EXPECT_EQ(s.usage.minor_faults, 2);  // ticks 3 and 4; ticks 0-2 are the warm-up
  const std::string json = loop_stats_json(s);
  EXPECT_NE(json.find("\"stalls\": [{\"wake_ns\": "), std::string::npos);
  EXPECT_NE(json.find("\"late_wakes\": 4"), std::string::npos);
}

}  // namespace
}  // namespace rgnav::lld
