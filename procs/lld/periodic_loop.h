// A fixed-rate loop on absolute deadlines: clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)
// to deadline k * period after the start, so sleeping late once does not shift later ticks.
// A tick that comes more than a period late counts the missed deadlines as overruns and
// re-aligns to the next one in the future. Period jitter (|actual - nominal| period) goes into
// a fixed histogram: recording never allocates, and another thread may read the counters.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace rgnav::lld {

struct LoopStats
{
  int64_t ticks = 0;
  int64_t overruns = 0;
  double jitter_max_ms = 0.0;
  double jitter_p50_ms = 0.0;
  double jitter_p99_ms = 0.0;
  double jitter_mean_ms = 0.0;
};

class PeriodicLoop
{
 public:
  struct Tick
  {
    int64_t index = 0;
    double dt = 0.0;          // [s] time since the previous tick (nominal period for the first)
    double jitter_ms = 0.0;   // |dt - period|
    int64_t missed = 0;       // deadlines skipped before this tick
  };

  explicit PeriodicLoop(std::chrono::nanoseconds period);

  // Sleeps until the next deadline; false if woken early by stop().
  bool wait(Tick* tick);
  // Makes wait() return false (from any thread).
  void stop() { stop_.store(true); }
  bool stopped() const { return stop_.load(); }

  std::chrono::nanoseconds period() const { return period_; }
  int64_t overruns() const { return overruns_.load(std::memory_order_relaxed); }
  LoopStats stats() const;

 private:
  static constexpr double kBinMs = 0.01;  // 10 us bins
  static constexpr size_t kBins = 10000;  // up to 100 ms; larger jitters land in the last bin
  void record(double jitter_ms);

  const std::chrono::nanoseconds period_;
  int64_t next_ns_ = 0;      // CLOCK_MONOTONIC deadline
  int64_t last_wake_ns_ = 0;
  int64_t index_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int64_t> ticks_{0};
  std::atomic<int64_t> overruns_{0};
  std::atomic<double> jitter_max_{0.0};
  std::atomic<double> jitter_sum_{0.0};
  std::array<std::atomic<uint32_t>, kBins> histogram_{};
};

}  // namespace rgnav::lld
