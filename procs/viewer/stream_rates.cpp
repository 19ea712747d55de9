#include "viewer/stream_rates.h"

namespace rgnav::viewer {

void StreamRates::note(const std::string& channel, int64_t utime, Clock::time_point at)
{
  auto it = entries_.find(channel);
  if (it == entries_.end()) {
    if (entries_.size() >= max_channels_) return;
    it = entries_.emplace(channel, Entry{}).first;
  }
  Entry& e = it->second;
  e.arrivals.push_back(at);
  while (e.arrivals.size() > kMaxArrivals || (!e.arrivals.empty() && at - e.arrivals.front() > window_))
    e.arrivals.pop_front();
  ++e.count;
  e.utime = utime;
}

std::vector<StreamRate> StreamRates::rates(Clock::time_point now) const
{
  std::vector<StreamRate> out;
  for (const auto& [channel, e] : entries_) {
    StreamRate r;
    r.channel = channel;
    r.count = e.count;
    r.utime = e.utime;
    if (!e.arrivals.empty()) {
      r.age_s = std::chrono::duration<double>(now - e.arrivals.back()).count();
      // Arrivals still inside the window as seen from now; a stream that stopped falls to 0.
      size_t first = 0;
      while (first < e.arrivals.size() && now - e.arrivals[first] > window_) ++first;
      const size_t n = e.arrivals.size() - first;
      if (n >= 2) {
        const double span = std::chrono::duration<double>(e.arrivals.back() - e.arrivals[first]).count();
        if (span > 0) r.hz = static_cast<double>(n - 1) / span;
      }
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace rgnav::viewer
