// The 0xB0 "all measured values" telegram (continuous output, operating mode 0x24):
//
//   data = COUNT (u16 LE) | VALUE[0] (u16 LE) ... VALUE[n-1]      then the status byte
//
// COUNT: bits 0..9 number of values, bits 11..12 partial-scan index (which 0.25° offset this
// rotation measured), bit 13 set when only a partial scan is sent, bits 14..15 units
// (00 cm, 01 mm, 10 dm). VALUE in measuring mode 0 (8 m / 80 m): bits 0..12 distance in the
// units, bits 13..15 the field A / field B / dazzle flags. Distances of 8183 and up are codes,
// not ranges: 8183 = beyond the measuring range (no return), 8184..8191 = invalid readings
// (dazzle, signal-to-noise too small, operation overflow, ...).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "commands.h"
#include "telegram.h"

namespace rgnav::drivers::sick {

constexpr uint16_t kValueMask = 0x1FFF;       // 13-bit distance
constexpr uint16_t kNoReturnCode = 8183;      // first code: measured value > maximum
constexpr uint16_t kMaxValidValue = kNoReturnCode - 1;
constexpr int kMaxValuesPerTelegram = 0x3FF;  // 10-bit count

struct MeasuredValues
{
  Units units = Units::kMillimetres;
  uint8_t partial_scan_index = 0;  // 0..3
  bool partial_scan = false;
  std::vector<uint16_t> values;    // 13-bit distances or codes
  std::vector<uint8_t> flags;      // bits 13..15 of each value, shifted down (0..7)
  uint8_t status = 0;              // telegram status byte
};

Telegram encode_measured_values(const MeasuredValues& m);
// nullopt when it is not a 0xB0 reply or COUNT disagrees with the telegram length.
std::optional<MeasuredValues> decode_measured_values(const Reply& r);

// What one raw value means.
enum class ValueKind { kRange, kNoReturn, kInvalid };
ValueKind classify_value(uint16_t value);

}  // namespace rgnav::drivers::sick
