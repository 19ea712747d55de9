// Typed publish/subscribe over a Bus. Every received message is checked before a handler
// sees it — fingerprint, lengths, finite numbers, enums (generated wire validators), then
// msg::semantically_valid — and dropped and counted if it fails, never decoded unchecked.
// Publishing checks the same, so a bug in a sender is caught where it is made.
#pragma once

#include <spdlog/spdlog.h>

#include <functional>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "bus/drop_counter.h"
#include "msg/semantic_checks.h"

namespace rgnav::bus {

// Encodes msg; false (with why) if counts and vectors disagree or a value is invalid.
template <class T>
bool encode(const T& msg, std::vector<uint8_t>* out, std::string* why)
{
  if (!counts_consistent(msg, why)) return false;
  if (!msg::semantically_valid(msg, why)) return false;
  out->resize(static_cast<size_t>(msg.getEncodedSize()));
  if (msg.encode(out->data(), 0, static_cast<int>(out->size())) < 0) {
    if (why) *why = "LCM encode failed";
    return false;
  }
  return wire::validate<T>(out->data(), out->size(), why);
}

// Checks, then decodes. Never allocates more than the message's own size implies.
template <class T>
bool decode(const uint8_t* data, size_t size, T* out, std::string* why)
{
  if (!wire::validate<T>(data, size, why)) return false;
  if (out->decode(data, 0, static_cast<int>(size)) < 0) {
    if (why) *why = "LCM decode failed";
    return false;
  }
  return msg::semantically_valid(*out, why);
}

template <class T>
bool publish(Bus& bus, const std::string& channel, const T& msg)
{
  std::vector<uint8_t> buf;
  std::string why;
  if (!encode(msg, &buf, &why)) {
    spdlog::error("not publishing invalid message on {}: {}", channel, why);
    return false;
  }
  return bus.publish(channel, buf.data(), buf.size());
}

template <class T>
using Handler = std::function<void(const T&, const RawMessage&)>;

// `drops` must outlive the subscription.
template <class T>
SubscriptionId subscribe(Bus& bus, const std::string& channel, Handler<T> handler, DropCounter* drops)
{
  return bus.subscribe(channel, [handler = std::move(handler), drops](const RawMessage& raw) {
    T msg;
    std::string why;
    if (!decode(raw.data, raw.size, &msg, &why)) {
      drops->drop(raw.channel, why);
      return;
    }
    handler(msg, raw);
  });
}

}  // namespace rgnav::bus
