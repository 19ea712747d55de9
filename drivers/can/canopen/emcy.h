// Emergency objects (EMCY), CiA 301 §7.2.7: COB-ID 0x80 + node, 8 bytes = error code (u16),
// error register (0x1001, u8), 5 manufacturer bytes. Error code 0x0000 = "error reset / no
// error", sent when a device leaves its error state.
#pragma once

#include <linux/can.h>

#include <cstdint>
#include <optional>
#include <string>

namespace rgnav::can::canopen::emcy {

// Error codes (CiA 301 Table 21, CiA 402 Table 5 for drive-specific codes).
constexpr uint16_t kNoError = 0x0000;
constexpr uint16_t kGeneric = 0x1000;
constexpr uint16_t kContinuousOverCurrent = 0x2310;
constexpr uint16_t kOverVoltage = 0x3210;
constexpr uint16_t kDriveTemperature = 0x4310;
constexpr uint16_t kHeartbeatError = 0x8130;  // life guard / heartbeat consumer event
constexpr uint16_t kRecoveredFromBusOff = 0x8140;
constexpr uint16_t kFollowingError = 0x8611;

// Error register bits (0x1001).
constexpr uint8_t kRegGeneric = 1u << 0;
constexpr uint8_t kRegCurrent = 1u << 1;
constexpr uint8_t kRegVoltage = 1u << 2;
constexpr uint8_t kRegTemperature = 1u << 3;
constexpr uint8_t kRegCommunication = 1u << 4;
constexpr uint8_t kRegProfile = 1u << 5;

struct Emergency
{
  uint8_t node_id = 0;
  uint16_t error_code = 0;
  uint8_t error_register = 0;
};

can_frame make(uint8_t node_id, uint16_t error_code, uint8_t error_register);
// nullopt unless the frame is an EMCY (0x81..0xFF, 8 bytes).
std::optional<Emergency> parse(const can_frame& f);
// The register bits that belong with an error code (what a device sets in 0x1001).
uint8_t register_for(uint16_t error_code);
std::string describe(uint16_t error_code);

}  // namespace rgnav::can::canopen::emcy
