// Message time: the only time algorithms may use. It advances with the utime of the inputs a
// process accepts, so lcm-logplayer replays and offline replays decide exactly as live runs.
// `int64_t utime` appears only at the LCM boundary (to_utime / from_utime).
#pragma once

#include <chrono>
#include <cstdint>

namespace rgnav::time {

// A clock tag for time points taken from messages (microseconds since the Unix epoch).
struct MessageClockTag
{
  using duration = std::chrono::microseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<MessageClockTag, duration>;
  static constexpr bool is_steady = false;
};

using Duration = std::chrono::microseconds;
using Time = MessageClockTag::time_point;

constexpr Time from_utime(int64_t utime) { return Time(Duration(utime)); }
constexpr int64_t to_utime(Time t) { return t.time_since_epoch().count(); }

template <class Rep, class Period>
constexpr double to_seconds(std::chrono::duration<Rep, Period> d)
{
  return std::chrono::duration<double>(d).count();
}

// Tracks the newest message time a process has accepted. Never goes backwards: an input with
// an older utime (out of order, or a replayed log restarting) does not move it. Nor does one
// stamped more than max_jump ahead, until a second input within confirm of it says the same
// (as time/robot_clock.h): one corrupted stamp would otherwise hold every message-time timer
// and age every input for as long as it is ahead.
class MessageClock
{
 public:
  static constexpr Duration kMaxJump{5'000'000};
  static constexpr Duration kConfirm{1'000'000};

  explicit MessageClock(Duration max_jump = kMaxJump, Duration confirm = kConfirm) : max_jump_(max_jump), confirm_(confirm) {}

  // Returns true when t advanced the clock.
  bool observe(Time t)
  {
    if (has_time_ && t <= now_) return false;
    if (has_time_ && t - now_ > max_jump_ && !(has_held_ && (t - held_ <= confirm_ && held_ - t <= confirm_))) {
      held_ = t;
      has_held_ = true;
      return false;
    }
    now_ = t;
    has_time_ = true;
    has_held_ = false;
    return true;
  }
  bool has_time() const { return has_time_; }
  Time now() const { return now_; }
  // Starting over (e.g. a log replay restarted from its beginning).
  void reset()
  {
    has_time_ = has_held_ = false;
    now_ = Time{};
  }

 private:
  Duration max_jump_, confirm_;
  Time now_{};
  bool has_time_ = false;
  Time held_{};  // a stamp far ahead, waiting for confirmation
  bool has_held_ = false;
};

// Wall time in utime, for the few places that must stamp real time: drivers stamping
// acquisitions and heartbeats. Algorithms never call this.
int64_t wall_utime();

}  // namespace rgnav::time
