#include "lld/periodic_loop.h"

#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <cerrno>

namespace rgnav::lld {

namespace {

// The calling thread's page faults and involuntary context switches so far.
StepUsage thread_usage()
{
  rusage ru{};
  getrusage(RUSAGE_THREAD, &ru);
  return {ru.ru_minflt, ru.ru_majflt, ru.ru_nivcsw};
}

StepUsage operator-(const StepUsage& a, const StepUsage& b)
{
  return {a.minor_faults - b.minor_faults, a.major_faults - b.major_faults,
          a.involuntary_switches - b.involuntary_switches};
}

}  // namespace

int64_t monotonic_ns()
{
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

PeriodicLoop::PeriodicLoop(std::chrono::nanoseconds period, double stall_ms, size_t max_stalls)
    : timeline_(period, stall_ms, max_stalls)
{
}

bool PeriodicLoop::wait(Tick* tick)
{
  const int64_t step_end = monotonic_ns();
  const StepUsage step_usage = thread_usage() - usage_at_wake_;
  if (!timeline_.started()) timeline_.start(step_end);
  // Sleep in slices of at most 100 ms so stop() is noticed even with long periods.
  const int64_t deadline = timeline_.next_deadline_ns();
  for (;;) {
    if (stop_.load()) return false;
    const int64_t now = monotonic_ns();
    if (now >= deadline) break;
    const int64_t target = std::min(deadline, now + 100'000'000);
    timespec ts{static_cast<time_t>(target / 1'000'000'000), static_cast<long>(target % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  const int64_t wake = monotonic_ns();
  usage_at_wake_ = thread_usage();
  *tick = timeline_.tick(step_end, wake, step_usage);
  return true;
}

}  // namespace rgnav::lld
