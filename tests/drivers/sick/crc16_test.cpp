// CRC and framing against telegrams as published for the LMS 2xx (the request bytes that
// every LMS driver and manual quotes), so the checksum is checked against the device's
// definition, not against our own encoder.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "commands.h"
#include "crc16.h"
#include "telegram.h"

namespace rgnav::drivers::sick {
namespace {

std::vector<uint8_t> hex(const std::string& s)
{
  std::vector<uint8_t> out;
  for (size_t i = 0; i + 1 < s.size(); i += 3) out.push_back(static_cast<uint8_t>(std::stoi(s.substr(i, 2), nullptr, 16)));
  return out;
}

struct Known
{
  const char* name;
  Telegram request;
  const char* bytes;
};

class KnownTelegrams : public ::testing::TestWithParam<Known>
{
};

TEST_P(KnownTelegrams, EncoderProducesThePublishedBytes)
{
  EXPECT_EQ(frame(GetParam().request), hex(GetParam().bytes)) << GetParam().name;
}

TEST_P(KnownTelegrams, CrcOfThePublishedBytes)
{
  const auto b = hex(GetParam().bytes);
  const uint16_t crc = crc16(b.data(), b.size() - 2);
  EXPECT_EQ(crc & 0xFF, b[b.size() - 2]);
  EXPECT_EQ(crc >> 8, b[b.size() - 1]);
}

INSTANTIATE_TEST_SUITE_P(
    Lms2xx, KnownTelegrams,
    ::testing::Values(Known{"continuous output", request_mode(OperatingMode::kContinuousAll), "02 00 02 00 20 24 34 08"},
                      Known{"stop (values on request)", request_mode(OperatingMode::kValuesOnRequest), "02 00 02 00 20 25 35 08"},
                      Known{"38400 baud", request_baud(Baud::k38400), "02 00 02 00 20 40 50 08"},
                      Known{"19200 baud", request_baud(Baud::k19200), "02 00 02 00 20 41 51 08"},
                      Known{"9600 baud", request_baud(Baud::k9600), "02 00 02 00 20 42 52 08"},
                      Known{"500000 baud", request_baud(Baud::k500000), "02 00 02 00 20 48 58 08"},
                      Known{"status", request_status(), "02 00 01 00 31 15 12"},
                      Known{"reset", request_reset(), "02 00 01 00 10 34 12"},
                      Known{"installation mode", request_installation_mode(), "02 00 0A 00 20 00 53 49 43 4B 5F 4C 4D 53 BE C5"},
                      Known{"variant 180/0.5", request_variant({180, 50}), "02 00 05 00 3B B4 00 32 00 3B 1F"},
                      Known{"variant 180/1", request_variant({180, 100}), "02 00 05 00 3B B4 00 64 00 97 49"},
                      Known{"variant 100/1", request_variant({100, 100}), "02 00 05 00 3B 64 00 64 00 1D 0F"}));

TEST(Crc16, EmptyIsZeroAndOneBitFlipChangesIt)
{
  EXPECT_EQ(crc16(nullptr, 0), 0);
  auto b = hex("02 00 02 00 20 24");
  const uint16_t good = crc16(b.data(), b.size());
  for (size_t i = 0; i < b.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      auto c = b;
      c[i] ^= static_cast<uint8_t>(1 << bit);
      EXPECT_NE(crc16(c.data(), c.size()), good) << "byte " << i << " bit " << bit;
    }
}

TEST(Crc16, IsNotTheReflectedArcCrc)
{
  // CRC-16/ARC of "123456789" is 0xBB3D; SICK's variant differs, so a generic CRC-16
  // would silently fail against real hardware.
  const std::string s = "123456789";
  EXPECT_NE(crc16(reinterpret_cast<const uint8_t*>(s.data()), s.size()), 0xBB3D);
}

}  // namespace
}  // namespace rgnav::drivers::sick
