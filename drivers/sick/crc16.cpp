#include "crc16.h"

namespace rgnav::drivers::sick {

uint16_t crc16(const uint8_t* data, size_t size)
{
  constexpr uint16_t kGenerator = 0x8005;
  uint16_t crc = 0;
  uint8_t previous = 0;
  for (size_t i = 0; i < size; ++i) {
    const uint8_t current = data[i];
    const bool top_bit = (crc & 0x8000) != 0;
    crc = static_cast<uint16_t>(crc << 1);
    if (top_bit) crc ^= kGenerator;
    // The byte pair (current, previous) enters as one little-endian word.
    crc ^= static_cast<uint16_t>(current | (previous << 8));
    previous = current;
  }
  return crc;
}

}  // namespace rgnav::drivers::sick
