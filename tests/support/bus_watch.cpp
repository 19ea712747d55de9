#include "bus_watch.h"

#include <cstdlib>

#include "bus/typed.h"

namespace rgnav::testing {

std::string test_udpm_url() { return "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"; }

bool in_private_netns()
{
  const char* v = std::getenv("RGNAV_NETNS");
  return v && std::string(v) == "1";
}

HeartbeatWatch::HeartbeatWatch(const std::string& url, const std::string& channel) : bus_(url)
{
  bus::subscribe<heartbeat_t>(
      bus_, channel,
      [this](const heartbeat_t& hb, const bus::RawMessage&) {
        seen_.push_back({hb, std::chrono::steady_clock::now()});
      },
      &drops_);
}

void HeartbeatWatch::pump(std::chrono::milliseconds max_wait) { bus_.handle(max_wait); }

std::optional<heartbeat_t> HeartbeatWatch::wait_until(const std::string& name, std::chrono::milliseconds timeout,
                                                      const std::function<bool(const heartbeat_t&)>& pred)
{
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  size_t checked = 0;
  for (;;) {
    for (; checked < seen_.size(); ++checked) {
      const auto& hb = seen_[checked].msg;
      if (hb.name == name && pred(hb)) return hb;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) return std::nullopt;
    pump(std::min(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now),
                  std::chrono::milliseconds(50)));
  }
}

std::optional<heartbeat_t> HeartbeatWatch::wait_for(const std::string& name, std::chrono::milliseconds timeout,
                                                    int32_t pid)
{
  return wait_until(name, timeout, [pid](const heartbeat_t& hb) { return pid <= 0 || hb.pid == pid; });
}

const std::vector<ReceivedHeartbeat>& HeartbeatWatch::collect(std::chrono::milliseconds duration)
{
  const auto deadline = std::chrono::steady_clock::now() + duration;
  for (auto now = std::chrono::steady_clock::now(); now < deadline; now = std::chrono::steady_clock::now())
    pump(std::min(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now),
                  std::chrono::milliseconds(50)));
  return seen_;
}

std::vector<ReceivedHeartbeat> HeartbeatWatch::from(const std::string& name) const
{
  std::vector<ReceivedHeartbeat> out;
  for (const auto& r : seen_)
    if (r.msg.name == name) out.push_back(r);
  return out;
}

}  // namespace rgnav::testing
