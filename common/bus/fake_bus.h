// A synchronous in-memory Bus for node tests: publish() delivers at once to matching
// subscribers (in the caller's thread) and records every message for inspection.
#pragma once

#include <map>
#include <regex>
#include <vector>

#include "bus/bus.h"

namespace rgnav::bus {

class FakeBus final : public Bus
{
 public:
  struct Published
  {
    std::string channel;
    std::vector<uint8_t> data;
  };

  bool publish(const std::string& channel, const void* data, size_t size) override;
  SubscriptionId subscribe(const std::string& channel, RawHandler handler) override;
  void unsubscribe(SubscriptionId id) override;
  int handle(std::chrono::milliseconds timeout) override;
  int fileno() const override { return -1; }
  std::string url() const override { return "fake://"; }

  const std::vector<Published>& published() const { return published_; }
  std::vector<Published> published_on(const std::string& channel) const;
  void clear() { published_.clear(); }
  // Simulates a failing transport: publish() returns false and delivers nothing.
  void set_fail_publish(bool fail) { fail_publish_ = fail; }

 private:
  struct Sub
  {
    std::regex pattern;
    RawHandler handler;
  };
  std::map<SubscriptionId, Sub> subs_;
  std::vector<Published> published_;
  SubscriptionId next_id_ = 1;
  bool fail_publish_ = false;
};

}  // namespace rgnav::bus
