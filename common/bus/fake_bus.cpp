#include "bus/fake_bus.h"

#include "time/message_time.h"

namespace rgnav::bus {

bool FakeBus::publish(const std::string& channel, const void* data, size_t size)
{
  if (fail_publish_) return false;
  const auto* bytes = static_cast<const uint8_t*>(data);
  published_.push_back({channel, std::vector<uint8_t>(bytes, bytes + size)});
  // Copy: a handler may publish (and so reallocate published_) or unsubscribe while we loop.
  const std::vector<uint8_t> copy(bytes, bytes + size);
  auto subs = subs_;
  for (auto& [id, sub] : subs) {
    if (!subs_.count(id) || !std::regex_match(channel, sub.pattern)) continue;
    sub.handler(RawMessage{channel, copy.data(), copy.size(), time::wall_utime()});
  }
  return true;
}

SubscriptionId FakeBus::subscribe(const std::string& channel, RawHandler handler)
{
  const SubscriptionId id = next_id_++;
  subs_[id] = Sub{std::regex(channel), std::move(handler)};
  return id;
}

void FakeBus::unsubscribe(SubscriptionId id) { subs_.erase(id); }

int FakeBus::handle(std::chrono::milliseconds) { return 0; }

std::vector<FakeBus::Published> FakeBus::published_on(const std::string& channel) const
{
  std::vector<Published> out;
  for (const auto& p : published_)
    if (p.channel == channel) out.push_back(p);
  return out;
}

}  // namespace rgnav::bus
