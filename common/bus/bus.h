// The messaging seam (Drake's DrakeLcmInterface idea): processes talk to a Bus, not to LCM.
// LcmBus is the real one (udpm://, file://, memq://); FakeBus delivers synchronously so node
// tests run without sockets or threads. Typed publish/subscribe with validation is in
// bus/typed.h on top of this raw interface.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace rgnav::bus {

struct RawMessage
{
  const std::string& channel;
  const uint8_t* data;
  size_t size;
  int64_t recv_utime;  // [us] wall time of reception (LCM's recv_utime; 0 where unknown)
};

using RawHandler = std::function<void(const RawMessage&)>;
using SubscriptionId = int;

class Bus
{
 public:
  virtual ~Bus() = default;
  // Returns false if the message could not be sent.
  virtual bool publish(const std::string& channel, const void* data, size_t size) = 0;
  // True when publish() may be called from another thread than handle()'s (the heartbeat
  // beside the loop); a bus that delivers synchronously (FakeBus) is not.
  virtual bool thread_safe_publish() const { return false; }
  // channel is an LCM channel regex (anchored: "LASER_FRONT" matches only that channel).
  virtual SubscriptionId subscribe(const std::string& channel, RawHandler handler) = 0;
  virtual void unsubscribe(SubscriptionId id) = 0;
  // Dispatches the messages waiting, blocking up to `timeout` for the first.
  // Returns the number of messages dispatched (0 on timeout), or -1 on a bus error.
  virtual int handle(std::chrono::milliseconds timeout) = 0;
  // A file descriptor that becomes readable when handle() has work, or -1 if there is none.
  virtual int fileno() const = 0;
  // The URL (or "fake://") this bus was made from, for log lines.
  virtual std::string url() const = 0;
};

}  // namespace rgnav::bus
