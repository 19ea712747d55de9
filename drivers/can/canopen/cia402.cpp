#include "canopen/cia402.h"

namespace rgnav::can::canopen::cia402 {

const char* to_string(PowerState s)
{
  switch (s) {
    case PowerState::kNotReadyToSwitchOn: return "not ready to switch on";
    case PowerState::kSwitchOnDisabled: return "switch on disabled";
    case PowerState::kReadyToSwitchOn: return "ready to switch on";
    case PowerState::kSwitchedOn: return "switched on";
    case PowerState::kOperationEnabled: return "operation enabled";
    case PowerState::kQuickStopActive: return "quick stop active";
    case PowerState::kFaultReactionActive: return "fault reaction active";
    case PowerState::kFault: return "fault";
  }
  return "?";
}

uint16_t statusword_bits(PowerState s)
{
  using namespace sw;
  switch (s) {
    case PowerState::kNotReadyToSwitchOn: return 0;
    case PowerState::kSwitchOnDisabled: return kSwitchOnDisabled;
    case PowerState::kReadyToSwitchOn: return kQuickStop | kReadyToSwitchOn;
    case PowerState::kSwitchedOn: return kQuickStop | kSwitchedOn | kReadyToSwitchOn;
    case PowerState::kOperationEnabled: return kQuickStop | kOperationEnabled | kSwitchedOn | kReadyToSwitchOn;
    case PowerState::kQuickStopActive: return kOperationEnabled | kSwitchedOn | kReadyToSwitchOn;
    case PowerState::kFaultReactionActive: return kFault | kOperationEnabled | kSwitchedOn | kReadyToSwitchOn;
    case PowerState::kFault: return kFault;
  }
  return 0;
}

PowerState decode_statusword(uint16_t s)
{
  // Table 31: x = don't care. Masks 0x4F (bits 0-3, 6) and 0x6F (plus bit 5).
  if ((s & 0x4F) == 0x00) return PowerState::kNotReadyToSwitchOn;
  if ((s & 0x4F) == 0x40) return PowerState::kSwitchOnDisabled;
  if ((s & 0x6F) == 0x21) return PowerState::kReadyToSwitchOn;
  if ((s & 0x6F) == 0x23) return PowerState::kSwitchedOn;
  if ((s & 0x6F) == 0x27) return PowerState::kOperationEnabled;
  if ((s & 0x6F) == 0x07) return PowerState::kQuickStopActive;
  if ((s & 0x4F) == 0x0F) return PowerState::kFaultReactionActive;
  if ((s & 0x4F) == 0x08) return PowerState::kFault;
  // Combinations Table 31 does not define: treat as not ready (nothing may move).
  return PowerState::kNotReadyToSwitchOn;
}

Command decode_controlword(uint16_t c, uint16_t previous)
{
  if ((c & cw::kFaultReset) && !(previous & cw::kFaultReset)) return Command::kFaultReset;
  if (!(c & cw::kEnableVoltage)) return Command::kDisableVoltage;   // xxxx xx0x
  if (!(c & cw::kQuickStop)) return Command::kQuickStop;            // xxxx x01x
  if (!(c & cw::kSwitchOn)) return Command::kShutdown;              // xxxx x110
  if (!(c & cw::kEnableOperation)) return Command::kSwitchOn;       // xxxx 0111
  return Command::kEnableOperation;                                 // xxxx 1111
}

uint16_t controlword_towards_enabled(PowerState state, uint16_t previous)
{
  switch (state) {
    case PowerState::kSwitchOnDisabled: return cw::kCmdShutdown;         // transition 2
    case PowerState::kReadyToSwitchOn: return cw::kCmdSwitchOn;          // transition 3
    case PowerState::kSwitchedOn: return cw::kCmdEnableOperation;        // transition 4
    case PowerState::kOperationEnabled: return cw::kCmdEnableOperation;  // stay
    case PowerState::kFault:
      // Transition 15 happens on the rising edge of bit 7: drop it first, then raise it.
      return (previous & cw::kFaultReset) ? cw::kCmdDisableVoltage : cw::kCmdFaultReset;
    case PowerState::kQuickStopActive:  // let the quick stop finish; it ends in switch on disabled
    case PowerState::kFaultReactionActive:
    case PowerState::kNotReadyToSwitchOn:
      return cw::kCmdDisableVoltage;
  }
  return cw::kCmdDisableVoltage;
}

}  // namespace rgnav::can::canopen::cia402
