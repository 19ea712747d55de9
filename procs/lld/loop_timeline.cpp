#include "lld/loop_timeline.h"

#include <algorithm>
#include <cmath>

namespace rgnav::lld {

LoopTimeline::LoopTimeline(std::chrono::nanoseconds period, double stall_ms, size_t max_stalls, int64_t warmup_ticks)
    : period_(period), stall_ms_(stall_ms), max_stalls_(max_stalls), warmup_ticks_(warmup_ticks)
{
  for (auto& b : histogram_) b.store(0, std::memory_order_relaxed);
  stalls_.reserve(max_stalls_);
}

void LoopTimeline::start(int64_t start_ns)
{
  started_ = true;
  next_ns_ = start_ns + period_.count();
  last_wake_ns_ = start_ns;
}

LoopTimeline::Tick LoopTimeline::tick(int64_t step_end_ns, int64_t wake_ns, const StepUsage& usage)
{
  const int64_t period = period_.count();
  const int64_t deadline = next_ns_;
  Tick t;
  t.index = index_++;
  t.dt = static_cast<double>(wake_ns - last_wake_ns_) * 1e-9;
  t.jitter_ms = std::fabs(static_cast<double>(wake_ns - last_wake_ns_ - period)) * 1e-6;
  const int64_t step_start_ns = last_wake_ns_;
  last_wake_ns_ = wake_ns;
  // Deadlines already passed (this tick ran more than a period late) are skipped, not run
  // back to back: each counts as an overrun.
  next_ns_ += period;
  while (next_ns_ <= wake_ns) {
    next_ns_ += period;
    ++t.missed;
  }
  if (t.missed) overruns_.fetch_add(t.missed, std::memory_order_relaxed);
  if (t.index > 0) {
    record(t.jitter_ms);
    const double step_ms = static_cast<double>(step_end_ns - step_start_ns) * 1e-6;
    if (step_ms > step_max_ms_.load(std::memory_order_relaxed)) step_max_ms_.store(step_ms, std::memory_order_relaxed);
    if (t.index > warmup_ticks_) {
      minor_faults_.fetch_add(usage.minor_faults, std::memory_order_relaxed);
      major_faults_.fetch_add(usage.major_faults, std::memory_order_relaxed);
      involuntary_switches_.fetch_add(usage.involuntary_switches, std::memory_order_relaxed);
    }
    // A stall is a late wake; the on-time tick after one also shows as jitter (a short
    // period), but nothing stalled there.
    const double late_ms = static_cast<double>(wake_ns - deadline) * 1e-6;
    if (late_ms > stall_ms_) {
      Stall s;
      s.wake_ns = wake_ns;
      s.jitter_ms = t.jitter_ms;
      s.late_ms = late_ms;
      s.step_ms = step_ms;
      s.step_overran = step_end_ns > deadline;
      s.missed = t.missed;
      s.usage = usage;
      keep_stall(s);
    }
  }
  ticks_.fetch_add(1, std::memory_order_relaxed);
  return t;
}

void LoopTimeline::keep_stall(const Stall& s)
{
  std::lock_guard<std::mutex> lock(stall_mutex_);
  ++(s.step_overran ? long_steps_ : late_wakes_);
  if (max_stalls_ == 0) return;
  if (stalls_.size() < max_stalls_) {
    stalls_.push_back(s);  // within the reserved capacity: no allocation
    return;
  }
  auto least = std::min_element(stalls_.begin(), stalls_.end(),
                                [](const Stall& a, const Stall& b) { return a.late_ms < b.late_ms; });
  if (least->late_ms < s.late_ms) *least = s;
}

void LoopTimeline::record(double jitter_ms)
{
  const size_t bin = std::min(kBins - 1, static_cast<size_t>(jitter_ms / kBinMs));
  histogram_[bin].fetch_add(1, std::memory_order_relaxed);
  if (jitter_ms > jitter_max_.load(std::memory_order_relaxed)) jitter_max_.store(jitter_ms, std::memory_order_relaxed);
  jitter_sum_.store(jitter_sum_.load(std::memory_order_relaxed) + jitter_ms, std::memory_order_relaxed);
}

LoopStats LoopTimeline::stats() const
{
  LoopStats s;
  s.ticks = ticks_.load();
  s.overruns = overruns_.load();
  s.jitter_max_ms = jitter_max_.load();
  s.step_max_ms = step_max_ms_.load();
  s.usage.minor_faults = minor_faults_.load();
  s.usage.major_faults = major_faults_.load();
  s.usage.involuntary_switches = involuntary_switches_.load();
  {
    std::lock_guard<std::mutex> lock(stall_mutex_);
    s.stalls = stalls_;
    s.long_steps = long_steps_;
    s.late_wakes = late_wakes_;
  }
  std::sort(s.stalls.begin(), s.stalls.end(), [](const Stall& a, const Stall& b) { return a.late_ms > b.late_ms; });
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
  s.jitter_p50_ms = std::min(quantile(0.50), s.jitter_max_ms);
  s.jitter_p99_ms = std::min(quantile(0.99), s.jitter_max_ms);
  return s;
}

}  // namespace rgnav::lld
