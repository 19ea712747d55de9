#include "telegram.h"

#include <stdexcept>

#include "crc16.h"

namespace rgnav::drivers::sick {

std::vector<uint8_t> frame(uint8_t address, const std::vector<uint8_t>& payload)
{
  if (payload.empty() || payload.size() > kMaxPayload)
    throw std::length_error("LMS telegram payload must hold 1.." + std::to_string(kMaxPayload) + " bytes");
  std::vector<uint8_t> out;
  out.reserve(framed_size(payload.size()));
  out.push_back(kStx);
  out.push_back(address);
  put_u16(&out, static_cast<uint16_t>(payload.size()));
  out.insert(out.end(), payload.begin(), payload.end());
  put_u16(&out, crc16(out.data(), out.size()));
  return out;
}

std::vector<uint8_t> frame(const Telegram& t) { return frame(t.address, t.payload); }

std::optional<Telegram> unframe(const uint8_t* bytes, size_t size)
{
  if (size < framed_size(1) || bytes[0] != kStx) return std::nullopt;
  const size_t len = get_u16(bytes + 2);
  if (len == 0 || len > kMaxPayload || size != framed_size(len)) return std::nullopt;
  if (crc16(bytes, kHeaderSize + len) != get_u16(bytes + kHeaderSize + len)) return std::nullopt;
  Telegram t;
  t.address = bytes[1];
  t.payload.assign(bytes + kHeaderSize, bytes + kHeaderSize + len);
  return t;
}

std::optional<Reply> as_reply(const Telegram& t)
{
  if (t.payload.size() < 2) return std::nullopt;
  Reply r;
  r.command = t.payload.front();
  r.data.assign(t.payload.begin() + 1, t.payload.end() - 1);
  r.status = t.payload.back();
  return r;
}

Telegram make_reply(uint8_t command, const std::vector<uint8_t>& data, uint8_t status)
{
  Telegram t;
  t.address = kAddressHost;
  t.payload.reserve(data.size() + 2);
  t.payload.push_back(command);
  t.payload.insert(t.payload.end(), data.begin(), data.end());
  t.payload.push_back(status);
  return t;
}

}  // namespace rgnav::drivers::sick
