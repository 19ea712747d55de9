// A fixed-rate loop on absolute deadlines: clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)
// to deadline k * period after the start, so sleeping late once does not shift later ticks.
// A tick that comes more than a period late counts the missed deadlines as overruns and
// re-aligns to the next one in the future. The timing account (jitter histogram, the worst
// stalls and whether the loop's own step or a late wake caused them) is LoopTimeline's;
// recording never allocates, and another thread may read the counters.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

#include "lld/loop_timeline.h"

namespace rgnav::lld {

class PeriodicLoop
{
 public:
  using Tick = LoopTimeline::Tick;

  explicit PeriodicLoop(std::chrono::nanoseconds period, double stall_ms = 5.0, size_t max_stalls = 32);

  // Sleeps until the next deadline; false if woken early by stop(). The time between two
  // calls is the step: how long it ran, and its page faults and preemptions, are recorded.
  bool wait(Tick* tick);
  // Makes wait() return false (from any thread).
  void stop() { stop_.store(true); }
  bool stopped() const { return stop_.load(); }

  std::chrono::nanoseconds period() const { return timeline_.period(); }
  int64_t overruns() const { return timeline_.overruns(); }
  LoopStats stats() const { return timeline_.stats(); }

 private:
  LoopTimeline timeline_;
  std::atomic<bool> stop_{false};
  StepUsage usage_at_wake_;  // the thread's counters when the current step began
};

// CLOCK_MONOTONIC now [ns]: the clock of every deadline and stall.
int64_t monotonic_ns();

}  // namespace rgnav::lld
