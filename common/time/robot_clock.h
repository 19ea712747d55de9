// The robot's time as a node reads it from the stamps of its inputs (message time, never the
// wall clock, so that a replayed log gives the same result). It only moves forward. A stamp
// more than max_jump ahead is held until a second input within confirm of it says the same: a
// single corrupted stamp would otherwise age every pose or end every goal at once (a drive
// loop whose inputs come at 50 Hz takes a tighter bound than a planner's). Stamps outside
// (0, 2^62) us are refused.
#pragma once

#include <cstdint>
#include <string>

namespace rgnav::time {

class RobotClock
{
 public:
  static constexpr int64_t kMaxJumpUs = 5'000'000;
  static constexpr int64_t kConfirmUs = 1'000'000;

  explicit RobotClock(int64_t max_jump_us = kMaxJumpUs, int64_t confirm_us = kConfirmUs)
      : max_jump_us_(max_jump_us), confirm_us_(confirm_us)
  {
  }

  // Empty when the stamp is taken (now() may have moved on); else why its input is dropped.
  // `channel` names the input in the log line of a confirmed jump.
  std::string observe(int64_t utime, const std::string& channel);
  // 0 until the first stamp.
  int64_t now() const { return now_; }

 private:
  int64_t max_jump_us_;
  int64_t confirm_us_;
  int64_t now_ = 0;
  int64_t held_ = 0;   // a stamp far ahead, waiting for confirmation
};

}  // namespace rgnav::time
