// Counts inputs a process refused (undecodable, invalid) and logs them without flooding:
// the first drop of a burst is logged at once, later ones are summed and reported at most
// once per second.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>

namespace rgnav::bus {

class DropCounter
{
 public:
  void drop(const std::string& channel, const std::string& why);
  int64_t total() const { return total_; }
  int64_t on_channel(const std::string& channel) const;

 private:
  using Clock = std::chrono::steady_clock;
  int64_t total_ = 0;
  std::map<std::string, int64_t> per_channel_;
  Clock::time_point last_log_{};
  int64_t unlogged_ = 0;
};

}  // namespace rgnav::bus
