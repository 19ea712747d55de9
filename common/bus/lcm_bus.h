// Bus over liblcm. URL as in lcm_create(): "" (LCM_DEFAULT_URL or the built-in default),
// "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608", "memq://", "file:///x.lcmlog?mode=r".
#pragma once

#include <lcm/lcm.h>

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "bus/bus.h"

namespace rgnav::bus {

class BusError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

class LcmBus final : public Bus
{
 public:
  // Throws BusError if LCM cannot be created from `url` (bad URL, no multicast route).
  explicit LcmBus(const std::string& url);
  ~LcmBus() override;
  LcmBus(const LcmBus&) = delete;
  LcmBus& operator=(const LcmBus&) = delete;

  bool publish(const std::string& channel, const void* data, size_t size) override;
  bool thread_safe_publish() const override { return true; }
  SubscriptionId subscribe(const std::string& channel, RawHandler handler) override;
  void unsubscribe(SubscriptionId id) override;
  int handle(std::chrono::milliseconds timeout) override;
  int fileno() const override;
  std::string url() const override { return url_; }

  // Messages LCM may queue per subscription before dropping (LCM default: 30).
  void set_queue_capacity(SubscriptionId id, int messages);

 private:
  struct Sub
  {
    RawHandler handler;
    lcm_subscription_t* lcm_sub = nullptr;
    std::string channel;
  };
  static void on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user);

  lcm_t* lcm_ = nullptr;
  std::mutex publish_mutex_;   // publishers on two threads (the heartbeat beside the loop)
  std::string url_;
  std::map<SubscriptionId, std::unique_ptr<Sub>> subs_;
  SubscriptionId next_id_ = 1;
};

}  // namespace rgnav::bus
