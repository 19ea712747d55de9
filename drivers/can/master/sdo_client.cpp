#include "master/sdo_client.h"

#include <cstdio>

#include "canopen/protocol.h"
#include "canopen/sdo.h"

namespace rgnav::can::master {

namespace sdo = canopen::sdo;

namespace {

std::string object_name(uint8_t node, uint16_t index, uint8_t sub)
{
  char buf[48];
  std::snprintf(buf, sizeof buf, "node %u object 0x%04X:%u", node, index, sub);
  return buf;
}

}  // namespace

void SdoClient::upload(uint8_t node, uint16_t index, uint8_t sub, Callback done)
{
  enqueue(node, Request{true, index, sub, 0, 4, std::move(done)});
}

void SdoClient::download(uint8_t node, uint16_t index, uint8_t sub, uint32_t value, uint8_t size, Callback done)
{
  enqueue(node, Request{false, index, sub, value, size, std::move(done)});
}

void SdoClient::enqueue(uint8_t node, Request r)
{
  channels_[node].queue.push_back(std::move(r));
  if (now_) start(node, channels_[node], *now_);
}

can_frame SdoClient::request_frame(uint8_t node, const Request& r) const
{
  return r.upload ? sdo::upload_request(node, r.index, r.sub) : sdo::download_request(node, r.index, r.sub, r.value, r.size);
}

void SdoClient::start(uint8_t node, Channel& ch, Clock::time_point now)
{
  if (ch.in_flight || ch.queue.empty()) return;
  ch.in_flight = true;
  ch.attempts = 1;
  ch.deadline = now + options_.timeout;
  send_(request_frame(node, ch.queue.front()));
}

void SdoClient::finish(uint8_t node, SdoResult result)
{
  auto it = channels_.find(node);
  if (it == channels_.end() || it->second.queue.empty()) return;
  Channel& ch = it->second;
  Request r = std::move(ch.queue.front());
  ch.queue.pop_front();
  ch.in_flight = false;
  if (!result.ok && result.error.empty()) {
    result.error = object_name(node, r.index, r.sub) + ": " +
                   (result.timed_out ? "no answer (timeout)" : "abort " + sdo::abort_text(result.abort_code));
  }
  // The callback may queue more requests for this node; start() then sends them.
  if (r.done) r.done(result);
  auto again = channels_.find(node);
  if (again != channels_.end() && now_) start(node, again->second, *now_);
}

bool SdoClient::handle(const can_frame& f, Clock::time_point now)
{
  now_ = now;
  const canid_t id = f.can_id & CAN_SFF_MASK;
  if (id <= canopen::kSdoTx || id > canopen::kSdoTx + 127 || (f.can_id & (CAN_EFF_FLAG | CAN_ERR_FLAG))) return false;
  const auto node = static_cast<uint8_t>(id - canopen::kSdoTx);
  auto it = channels_.find(node);
  if (it == channels_.end() || !it->second.in_flight) return false;
  const Request& r = it->second.queue.front();
  const sdo::Message m = sdo::parse(f);
  SdoResult res;
  if (m.type == sdo::Message::Type::kAbort) {
    res.abort_code = m.abort_code;
    finish(node, res);
    return true;
  }
  if (m.index != r.index || m.subindex != r.sub) return true;  // a late answer to an older request
  if (r.upload && m.type == sdo::Message::Type::kUploadResponse) {
    res.ok = true;
    res.value = m.value;
    res.size = m.size;
  } else if (!r.upload && m.type == sdo::Message::Type::kDownloadResponse) {
    res.ok = true;
  } else {
    // Wrong kind of answer, or a segmented upload we do not speak: abort the transfer.
    res.abort_code = sdo::kBadCommand;
    send_(sdo::abort(canopen::kSdoRx + node, r.index, r.sub, sdo::kBadCommand));
  }
  finish(node, res);
  return true;
}

void SdoClient::tick(Clock::time_point now)
{
  now_ = now;
  // Collect first: finish() may change channels_.
  std::vector<uint8_t> expired;
  for (auto& [node, ch] : channels_) {
    if (!ch.in_flight) {
      start(node, ch, now);
      continue;
    }
    if (now < ch.deadline) continue;
    if (ch.attempts <= options_.retries) {
      ++ch.attempts;
      ch.deadline = now + options_.timeout;
      send_(request_frame(node, ch.queue.front()));
    } else {
      expired.push_back(node);
    }
  }
  for (uint8_t node : expired) {
    const Request& r = channels_[node].queue.front();
    send_(sdo::abort(canopen::kSdoRx + node, r.index, r.sub, sdo::kTimeout));
    SdoResult res;
    res.timed_out = true;
    res.abort_code = sdo::kTimeout;
    finish(node, res);
  }
}

void SdoClient::cancel(uint8_t node) { channels_.erase(node); }

bool SdoClient::idle(uint8_t node) const
{
  const auto it = channels_.find(node);
  return it == channels_.end() || (!it->second.in_flight && it->second.queue.empty());
}

}  // namespace rgnav::can::master
