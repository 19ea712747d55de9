#include "bus/lcm_bus.h"

#include <poll.h>

namespace rgnav::bus {

LcmBus::LcmBus(const std::string& url) : url_(url)
{
  lcm_ = lcm_create(url.empty() ? nullptr : url.c_str());
  if (!lcm_) throw BusError("cannot create LCM from URL '" + url + "' (bad URL, or no multicast route?)");
}

LcmBus::~LcmBus()
{
  for (auto& [id, sub] : subs_) lcm_unsubscribe(lcm_, sub->lcm_sub);
  lcm_destroy(lcm_);
}

bool LcmBus::publish(const std::string& channel, const void* data, size_t size)
{
  const std::lock_guard<std::mutex> lock(publish_mutex_);
  return lcm_publish(lcm_, channel.c_str(), data, static_cast<unsigned int>(size)) == 0;
}

void LcmBus::on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
  auto* sub = static_cast<Sub*>(user);
  const std::string ch(channel);
  sub->handler(RawMessage{ch, static_cast<const uint8_t*>(rbuf->data), rbuf->data_size, rbuf->recv_utime});
}

SubscriptionId LcmBus::subscribe(const std::string& channel, RawHandler handler)
{
  auto sub = std::make_unique<Sub>();
  sub->handler = std::move(handler);
  sub->channel = channel;
  sub->lcm_sub = lcm_subscribe(lcm_, channel.c_str(), &LcmBus::on_message, sub.get());
  if (!sub->lcm_sub) throw BusError("cannot subscribe to '" + channel + "'");
  const SubscriptionId id = next_id_++;
  subs_[id] = std::move(sub);
  return id;
}

void LcmBus::unsubscribe(SubscriptionId id)
{
  auto it = subs_.find(id);
  if (it == subs_.end()) return;
  lcm_unsubscribe(lcm_, it->second->lcm_sub);
  subs_.erase(it);
}

void LcmBus::set_queue_capacity(SubscriptionId id, int messages)
{
  auto it = subs_.find(id);
  if (it != subs_.end()) lcm_subscription_set_queue_capacity(it->second->lcm_sub, messages);
}

int LcmBus::handle(std::chrono::milliseconds timeout)
{
  // Dispatch everything already waiting, but wait at most `timeout` for the first message.
  int dispatched = 0;
  int wait_ms = static_cast<int>(timeout.count());
  for (;;) {
    const int r = lcm_handle_timeout(lcm_, wait_ms);
    if (r < 0) return dispatched > 0 ? dispatched : -1;
    if (r == 0) return dispatched;
    ++dispatched;
    wait_ms = 0;
    if (dispatched >= 1000) return dispatched;  // let the caller's timers run under a flood
  }
}

int LcmBus::fileno() const { return lcm_get_fileno(lcm_); }

}  // namespace rgnav::bus
