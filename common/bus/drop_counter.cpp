#include "bus/drop_counter.h"

#include <spdlog/spdlog.h>

namespace rgnav::bus {

void DropCounter::drop(const std::string& channel, const std::string& why)
{
  ++total_;
  ++per_channel_[channel];
  const auto now = Clock::now();
  if (now - last_log_ < std::chrono::seconds(1)) {
    ++unlogged_;
    return;
  }
  if (unlogged_ > 0)
    spdlog::warn("dropped {} more input messages in the last burst ({} in total)", unlogged_, total_);
  spdlog::warn("dropped a message on {}: {}", channel, why);
  unlogged_ = 0;
  last_log_ = now;
}

int64_t DropCounter::on_channel(const std::string& channel) const
{
  auto it = per_channel_.find(channel);
  return it == per_channel_.end() ? 0 : it->second;
}

}  // namespace rgnav::bus
