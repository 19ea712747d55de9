#include "lld/periodic_loop.h"

#include <time.h>

#include <cmath>

namespace rgnav::lld {

namespace {

int64_t monotonic_ns()
{
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

PeriodicLoop::PeriodicLoop(std::chrono::nanoseconds period) : period_(period)
{
  for (auto& b : histogram_) b.store(0, std::memory_order_relaxed);
}

bool PeriodicLoop::wait(Tick* tick)
{
  const int64_t period = period_.count();
  if (index_ == 0) {
    next_ns_ = monotonic_ns() + period;
    last_wake_ns_ = next_ns_ - period;
  }
  // Sleep in slices of at most 100 ms so stop() is noticed even with long periods.
  for (;;) {
    if (stop_.load()) return false;
    const int64_t now = monotonic_ns();
    if (now >= next_ns_) break;
    const int64_t target = std::min(next_ns_, now + 100'000'000);
    timespec ts{static_cast<time_t>(target / 1'000'000'000), static_cast<long>(target % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  const int64_t wake = monotonic_ns();
  tick->index = index_++;
  tick->dt = static_cast<double>(wake - last_wake_ns_) * 1e-9;
  tick->jitter_ms = std::fabs(static_cast<double>(wake - last_wake_ns_ - period)) * 1e-6;
  last_wake_ns_ = wake;
  // Deadlines already passed (this tick ran more than a period late) are skipped, not run
  // back to back: each counts as an overrun.
  tick->missed = 0;
  next_ns_ += period;
  while (next_ns_ <= wake) {
    next_ns_ += period;
    ++tick->missed;
  }
  if (tick->missed) overruns_.fetch_add(tick->missed, std::memory_order_relaxed);
  if (tick->index > 0) record(tick->jitter_ms);
  ticks_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void PeriodicLoop::record(double jitter_ms)
{
  const size_t bin = std::min(kBins - 1, static_cast<size_t>(jitter_ms / kBinMs));
  histogram_[bin].fetch_add(1, std::memory_order_relaxed);
  if (jitter_ms > jitter_max_.load(std::memory_order_relaxed)) jitter_max_.store(jitter_ms, std::memory_order_relaxed);
  jitter_sum_.store(jitter_sum_.load(std::memory_order_relaxed) + jitter_ms, std::memory_order_relaxed);
}

LoopStats PeriodicLoop::stats() const
{
  LoopStats s;
  s.ticks = ticks_.load();
  s.overruns = overruns_.load();
  s.jitter_max_ms = jitter_max_.load();
  uint64_t total = 0;
  for (const auto& b : histogram_) total += b.load(std::memory_order_relaxed);
  if (total == 0) return s;
  s.jitter_mean_ms = jitter_sum_.load() / static_cast<double>(total);
  auto quantile = [&](double q) {
    const uint64_t want = static_cast<uint64_t>(std::ceil(q * static_cast<double>(total)));
    uint64_t acc = 0;
    for (size_t i = 0; i < kBins; ++i) {
      acc += histogram_[i].load(std::memory_order_relaxed);
      if (acc >= want) return (static_cast<double>(i) + 1.0) * kBinMs;  // upper edge of the bin
    }
    return static_cast<double>(kBins) * kBinMs;
  };
  s.jitter_p50_ms = quantile(0.50);
  s.jitter_p99_ms = std::min(quantile(0.99), s.jitter_max_ms);
  s.jitter_p50_ms = std::min(s.jitter_p50_ms, s.jitter_max_ms);
  return s;
}

}  // namespace rgnav::lld
