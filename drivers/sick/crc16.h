// The CRC-16 of the SICK LMS 2xx telegram listing: generator polynomial 0x8005, initial value
// 0, computed over every byte of a telegram from STX up to (not including) the CRC, and sent
// low byte first. It is NOT the common reflected CRC-16/ARC: SICK's routine xors each new byte
// together with the previous one (as a 16-bit word, new byte low) into the shifted register,
// so a table-driven CRC-16 from elsewhere gives wrong checksums.
#pragma once

#include <cstddef>
#include <cstdint>

namespace rgnav::drivers::sick {

uint16_t crc16(const uint8_t* data, size_t size);

}  // namespace rgnav::drivers::sick
