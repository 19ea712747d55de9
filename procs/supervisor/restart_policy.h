// When to restart a process that stopped on its own: exponential back-off, and a restart
// intensity limit (at most max_restarts in window; one more and the process is given up).
// Pure logic on a steady clock, so it is tested without processes.
#pragma once

#include <chrono>
#include <deque>

namespace rgnav::supervisor {

struct RestartOptions
{
  std::chrono::milliseconds initial_backoff{100};
  std::chrono::milliseconds max_backoff{5000};
  double backoff_factor = 2.0;
  int max_restarts = 5;                 // within `window`
  std::chrono::milliseconds window{30000};
  // Running this long without failing resets the back-off to its initial value.
  std::chrono::milliseconds stable_after{10000};
};

class RestartPolicy
{
 public:
  using Clock = std::chrono::steady_clock;

  explicit RestartPolicy(RestartOptions options) : options_(options) {}

  struct Decision
  {
    bool give_up = false;                 // intensity exceeded: mark FAILED
    std::chrono::milliseconds delay{0};   // back-off before the restart
  };
  // A failure at `now` of a process that had been running since `started`.
  Decision on_failure(Clock::time_point now, Clock::time_point started);
  // An operator start/restart: forget the history.
  void reset();
  int restarts_in_window(Clock::time_point now) const;

 private:
  RestartOptions options_;
  std::deque<Clock::time_point> restarts_;
  std::chrono::milliseconds next_delay_{-1};
};

}  // namespace rgnav::supervisor
