#include "time/robot_clock.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>

namespace rgnav::time {

namespace {

constexpr int64_t kMaxStamp = int64_t{1} << 62;

}  // namespace

std::string RobotClock::observe(int64_t utime, const std::string& channel)
{
  if (utime <= 0 || utime >= kMaxStamp) return "utime out of range";
  if (now_ == 0 || utime <= now_ + max_jump_us_) {
    now_ = std::max(now_, utime);
    held_ = 0;
    return "";
  }
  if (held_ != 0 && std::llabs(utime - held_) <= confirm_us_) {
    spdlog::warn("robot time jumped ahead by {:.1f} s (confirmed by {})", static_cast<double>(utime - now_) * 1e-6, channel);
    now_ = utime;
    held_ = 0;
    return "";
  }
  held_ = utime;
  return fmt::format("stamp {:.1f} s ahead of the robot's time (used once another input confirms it)",
                     static_cast<double>(utime - now_) * 1e-6);
}

}  // namespace rgnav::time
