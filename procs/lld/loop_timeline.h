// The timing account of a fixed-rate loop: given when each step ended and when the loop woke
// for the next, it keeps the deadlines (k * period after the start), counts overruns, bins
// the period jitter (|actual - nominal| period) into a fixed histogram, and keeps the worst
// stalls with what tells their cause apart:
//   - the step itself ran past the next deadline (the loop's own work blocked: a lock held by
//     a preempted thread, a page fault, a publish waiting on a socket), or
//   - the step ended in time but the thread got the CPU late (the scheduler, or the machine:
//     a virtual CPU the host did not run).
// The wake times are CLOCK_MONOTONIC, the same clock in every process, so stalls seen by two
// processes can be matched in time (deploy/bench/control.sh runs a canary loop beside the lld).
// PeriodicLoop does the sleeping; this class only does arithmetic, so tests feed it times.
// Recording never allocates; another thread may read the counters and stats().
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <vector>

namespace rgnav::lld {

// What the thread used during one step (getrusage(RUSAGE_THREAD) differences).
struct StepUsage
{
  int64_t minor_faults = 0;
  int64_t major_faults = 0;
  int64_t involuntary_switches = 0;  // preempted during the step
};

// One tick that woke more than the stall threshold after its deadline.
struct Stall
{
  int64_t wake_ns = 0;      // CLOCK_MONOTONIC when the late tick woke
  double jitter_ms = 0.0;   // |period seen - nominal|
  double late_ms = 0.0;     // wake - deadline: how late the loop got going
  double step_ms = 0.0;     // how long the step before it ran (its end - its wake)
  bool step_overran = false;  // that step ended after this tick's deadline: the loop's own work
  int64_t missed = 0;       // deadlines skipped
  StepUsage usage;          // of the step before it
};

struct LoopStats
{
  int64_t ticks = 0;
  int64_t overruns = 0;
  double jitter_max_ms = 0.0;
  double jitter_p50_ms = 0.0;
  double jitter_p99_ms = 0.0;
  double jitter_mean_ms = 0.0;
  double step_max_ms = 0.0;     // longest step (the loop's own work per period)
  int64_t long_steps = 0;       // stalls whose step ran past the deadline
  int64_t late_wakes = 0;       // stalls of a step that ended in time
  StepUsage usage;              // summed over all steps after the first `warmup_ticks`
  std::vector<Stall> stalls;    // the worst, latest wake first
};

class LoopTimeline
{
 public:
  // Ticks waking more than stall_ms after their deadline are stalls; the worst max_stalls are kept. The
  // first warmup_ticks steps (the loop's first touches of its memory) are left out of usage.
  explicit LoopTimeline(std::chrono::nanoseconds period, double stall_ms = 5.0, size_t max_stalls = 32,
                        int64_t warmup_ticks = 10);

  struct Tick
  {
    int64_t index = 0;
    double dt = 0.0;          // [s] time since the previous tick (nominal period for the first)
    double jitter_ms = 0.0;   // |dt - period|
    int64_t missed = 0;       // deadlines skipped before this tick
  };

  // The loop starts at start_ns: the first deadline is one period later.
  void start(int64_t start_ns);
  bool started() const { return started_; }
  int64_t next_deadline_ns() const { return next_ns_; }
  // The loop woke at wake_ns >= next_deadline_ns(); the step before ended at step_end_ns
  // (ignored for the first tick) using `usage`. Advances the deadline past wake_ns.
  Tick tick(int64_t step_end_ns, int64_t wake_ns, const StepUsage& usage);

  std::chrono::nanoseconds period() const { return period_; }
  int64_t overruns() const { return overruns_.load(std::memory_order_relaxed); }
  LoopStats stats() const;

 private:
  static constexpr double kBinMs = 0.01;  // 10 us bins
  static constexpr size_t kBins = 10000;  // up to 100 ms; larger jitters land in the last bin
  void record(double jitter_ms);
  void keep_stall(const Stall& s);

  const std::chrono::nanoseconds period_;
  const double stall_ms_;
  const size_t max_stalls_;
  const int64_t warmup_ticks_;
  bool started_ = false;
  int64_t next_ns_ = 0;
  int64_t last_wake_ns_ = 0;
  int64_t index_ = 0;
  std::atomic<int64_t> ticks_{0};
  std::atomic<int64_t> overruns_{0};
  std::atomic<double> jitter_max_{0.0};
  std::atomic<double> jitter_sum_{0.0};
  std::array<std::atomic<uint32_t>, kBins> histogram_{};
  // Rarely written (stalls only): a plain lock, never taken on an ordinary tick.
  mutable std::mutex stall_mutex_;
  std::vector<Stall> stalls_;  // capacity max_stalls_, reserved up front; unsorted
  int64_t long_steps_ = 0;
  int64_t late_wakes_ = 0;
  std::atomic<double> step_max_ms_{0.0};
  std::atomic<int64_t> minor_faults_{0};
  std::atomic<int64_t> major_faults_{0};
  std::atomic<int64_t> involuntary_switches_{0};
};

}  // namespace rgnav::lld
