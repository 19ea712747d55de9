// The time and rate of each input stream, for the page's stream table. Memory is bounded: a
// few arrival times per channel and at most max_channels channels (a flood of made-up channel
// names cannot grow it).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

namespace rgnav::viewer {

struct StreamRate
{
  std::string channel;
  double hz = 0;          // over the arrivals of the last window
  double age_s = -1;      // since the newest arrival (-1: never)
  int64_t count = 0;      // since start
  int64_t utime = 0;      // message time of the newest
};

class StreamRates
{
 public:
  using Clock = std::chrono::steady_clock;
  explicit StreamRates(Clock::duration window = std::chrono::seconds(5), size_t max_channels = 64)
      : window_(window), max_channels_(max_channels) {}

  void note(const std::string& channel, int64_t utime, Clock::time_point at);
  std::vector<StreamRate> rates(Clock::time_point now) const;

 private:
  struct Entry
  {
    std::deque<Clock::time_point> arrivals;   // within the window, at most kMaxArrivals
    int64_t count = 0;
    int64_t utime = 0;
  };
  static constexpr size_t kMaxArrivals = 256;
  Clock::duration window_;
  size_t max_channels_;
  std::map<std::string, Entry> entries_;
};

}  // namespace rgnav::viewer
