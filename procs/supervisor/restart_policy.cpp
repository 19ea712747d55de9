#include "restart_policy.h"

#include <algorithm>

namespace rgnav::supervisor {

RestartPolicy::Decision RestartPolicy::on_failure(Clock::time_point now, Clock::time_point started)
{
  while (!restarts_.empty() && now - restarts_.front() > options_.window) restarts_.pop_front();
  if (next_delay_.count() < 0 || now - started >= options_.stable_after) next_delay_ = options_.initial_backoff;

  Decision d;
  if (static_cast<int>(restarts_.size()) >= options_.max_restarts) {
    d.give_up = true;
    return d;
  }
  d.delay = next_delay_;
  restarts_.push_back(now);
  const auto grown = std::chrono::milliseconds(static_cast<int64_t>(next_delay_.count() * options_.backoff_factor));
  next_delay_ = std::min(grown, options_.max_backoff);
  return d;
}

void RestartPolicy::reset()
{
  restarts_.clear();
  next_delay_ = std::chrono::milliseconds(-1);
}

int RestartPolicy::restarts_in_window(Clock::time_point now) const
{
  return static_cast<int>(std::count_if(restarts_.begin(), restarts_.end(),
                                        [&](Clock::time_point t) { return now - t <= options_.window; }));
}

}  // namespace rgnav::supervisor
