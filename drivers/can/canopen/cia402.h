// CiA 402 (drives and motion control) power state machine, shared by the master (which reads
// the statusword and writes controlwords) and the drive emulator (which does the opposite).
// CiA 402-2 §6.4 (state machine), Tables 30 (controlword commands) and 31 (statusword).
#pragma once

#include <cstdint>

namespace rgnav::can::canopen::cia402 {

// Objects of the profile used here.
constexpr uint16_t kControlword = 0x6040;
constexpr uint16_t kStatusword = 0x6041;
constexpr uint16_t kQuickStopOptionCode = 0x605A;
constexpr uint16_t kModesOfOperation = 0x6060;
constexpr uint16_t kModesOfOperationDisplay = 0x6061;
constexpr uint16_t kPositionActual = 0x6064;
constexpr uint16_t kVelocityDemand = 0x606B;
constexpr uint16_t kVelocityActual = 0x606C;
constexpr uint16_t kProfileAcceleration = 0x6083;
constexpr uint16_t kProfileDeceleration = 0x6084;
constexpr uint16_t kQuickStopDeceleration = 0x6085;
constexpr uint16_t kMaxProfileVelocity = 0x607F;
constexpr uint16_t kTargetVelocity = 0x60FF;
constexpr uint16_t kSupportedDriveModes = 0x6502;

constexpr int8_t kModeProfileVelocity = 3;
constexpr uint32_t kSupportsProfileVelocity = 1u << 2;  // bit of 0x6502
constexpr uint16_t kDeviceProfile = 402;               // low 16 bits of 0x1000

namespace sw {
constexpr uint16_t kReadyToSwitchOn = 1u << 0;
constexpr uint16_t kSwitchedOn = 1u << 1;
constexpr uint16_t kOperationEnabled = 1u << 2;
constexpr uint16_t kFault = 1u << 3;
constexpr uint16_t kVoltageEnabled = 1u << 4;
constexpr uint16_t kQuickStop = 1u << 5;  // 0 = quick stop active
constexpr uint16_t kSwitchOnDisabled = 1u << 6;
constexpr uint16_t kWarning = 1u << 7;
constexpr uint16_t kRemote = 1u << 9;
constexpr uint16_t kTargetReached = 1u << 10;
constexpr uint16_t kInternalLimit = 1u << 11;
}  // namespace sw

namespace cw {
constexpr uint16_t kSwitchOn = 1u << 0;
constexpr uint16_t kEnableVoltage = 1u << 1;
constexpr uint16_t kQuickStop = 1u << 2;  // 0 = quick stop
constexpr uint16_t kEnableOperation = 1u << 3;
constexpr uint16_t kFaultReset = 1u << 7;
constexpr uint16_t kHalt = 1u << 8;
// Whole command words.
constexpr uint16_t kCmdShutdown = 0x0006;
constexpr uint16_t kCmdSwitchOn = 0x0007;
constexpr uint16_t kCmdEnableOperation = 0x000F;
constexpr uint16_t kCmdDisableVoltage = 0x0000;
constexpr uint16_t kCmdQuickStop = 0x0002;
constexpr uint16_t kCmdFaultReset = 0x0080;
}  // namespace cw

enum class PowerState : uint8_t
{
  kNotReadyToSwitchOn,
  kSwitchOnDisabled,
  kReadyToSwitchOn,
  kSwitchedOn,
  kOperationEnabled,
  kQuickStopActive,
  kFaultReactionActive,
  kFault,
};
const char* to_string(PowerState s);

// The statusword state bits (CiA 402 Table 31) of a state; other bits are the caller's.
uint16_t statusword_bits(PowerState s);
PowerState decode_statusword(uint16_t statusword);

// The device-control command a controlword carries (bits 0-3 and 7, CiA 402 Table 30).
// Fault reset is the 0->1 edge of bit 7, so it needs the previous controlword.
enum class Command : uint8_t
{
  kShutdown,
  kSwitchOn,             // also "disable operation" when coming from Operation enabled
  kEnableOperation,      // "switch on + enable operation" from Ready to switch on
  kDisableVoltage,
  kQuickStop,
  kFaultReset,
};
Command decode_controlword(uint16_t controlword, uint16_t previous_controlword);

// Master side: the controlword that moves a drive in `state` one step towards Operation
// enabled (in Fault, a fault reset edge needs `previous` without bit 7 first).
uint16_t controlword_towards_enabled(PowerState state, uint16_t previous);

}  // namespace rgnav::can::canopen::cia402
