#include "shared_silence.h"

#include <algorithm>

namespace rgnav::supervisor {

std::chrono::steady_clock::duration silence_window(std::chrono::milliseconds configured, std::chrono::milliseconds bound)
{
  return std::min<std::chrono::steady_clock::duration>(configured, bound / 2);
}

bool began_together(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b,
                    std::chrono::steady_clock::duration window)
{
  return (a > b ? a - b : b - a) <= window;
}

void SharedSilence::hold(const std::string& name, Clock::time_point newest_beat)
{
  if (held_ == 0) {
    // A new shared silence.
    counted_ = false;
    newest_beat_ = newest_beat;
    names_.clear();
  }
  ++held_;
  newest_beat_ = std::max(newest_beat_, newest_beat);
  if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
}

std::optional<SharedSilence::Clock::duration> SharedSilence::heard(Clock::time_point now)
{
  release();
  if (counted_) return std::nullopt;
  counted_ = true;
  return std::max(Clock::duration::zero(), now - newest_beat_);
}

void SharedSilence::release()
{
  if (held_ > 0) --held_;
}

void SharedSilence::shift(Clock::duration gap, Clock::time_point now)
{
  if (held_ > 0) newest_beat_ = std::min(newest_beat_ + gap, now);
}

std::string SharedSilence::names() const
{
  std::string out;
  for (const auto& n : names_) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace rgnav::supervisor
