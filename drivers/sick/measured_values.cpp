#include "measured_values.h"

#include <stdexcept>

namespace rgnav::drivers::sick {

Telegram encode_measured_values(const MeasuredValues& m)
{
  if (m.values.size() > static_cast<size_t>(kMaxValuesPerTelegram))
    throw std::length_error("0xB0 telegram holds at most 1023 values");
  if (!m.flags.empty() && m.flags.size() != m.values.size())
    throw std::invalid_argument("0xB0 flags must be empty or one per value");
  std::vector<uint8_t> d;
  d.reserve(2 + 2 * m.values.size());
  const uint16_t count = static_cast<uint16_t>(m.values.size() | ((m.partial_scan_index & 0x3) << 11) |
                                               (m.partial_scan ? 1 << 13 : 0) |
                                               ((static_cast<uint16_t>(m.units) & 0x3) << 14));
  put_u16(&d, count);
  for (size_t i = 0; i < m.values.size(); ++i) {
    const uint16_t flags = m.flags.empty() ? 0 : static_cast<uint16_t>((m.flags[i] & 0x7) << 13);
    put_u16(&d, static_cast<uint16_t>((m.values[i] & kValueMask) | flags));
  }
  return make_reply(reply::kMeasuredValues, d, m.status);
}

std::optional<MeasuredValues> decode_measured_values(const Reply& r)
{
  if (r.command != reply::kMeasuredValues || r.data.size() < 2) return std::nullopt;
  const uint16_t count_word = get_u16(r.data.data());
  const size_t n = count_word & 0x3FF;
  if (r.data.size() != 2 + 2 * n) return std::nullopt;
  MeasuredValues m;
  m.partial_scan_index = static_cast<uint8_t>((count_word >> 11) & 0x3);
  m.partial_scan = (count_word >> 13) & 0x1;
  const uint8_t unit_bits = static_cast<uint8_t>(count_word >> 14);
  if (unit_bits == 0x3) return std::nullopt;  // reserved
  m.units = static_cast<Units>(unit_bits);
  m.values.resize(n);
  m.flags.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const uint16_t v = get_u16(&r.data[2 + 2 * i]);
    m.values[i] = v & kValueMask;
    m.flags[i] = static_cast<uint8_t>(v >> 13);
  }
  m.status = r.status;
  return m;
}

ValueKind classify_value(uint16_t value)
{
  if (value < kNoReturnCode) return ValueKind::kRange;
  if (value == kNoReturnCode) return ValueKind::kNoReturn;
  return ValueKind::kInvalid;
}

}  // namespace rgnav::drivers::sick
