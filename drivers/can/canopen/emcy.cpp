#include "canopen/emcy.h"

#include <cstdio>

#include "bus/can_frames.h"
#include "canopen/protocol.h"

namespace rgnav::can::canopen::emcy {

can_frame make(uint8_t node_id, uint16_t error_code, uint8_t error_register)
{
  return make_frame(kEmcyBase + node_id,
                    {static_cast<uint8_t>(error_code & 0xFF), static_cast<uint8_t>(error_code >> 8), error_register, 0,
                     0, 0, 0, 0});
}

std::optional<Emergency> parse(const can_frame& f)
{
  if (is_error_frame(f) || is_extended(f)) return std::nullopt;
  const canid_t id = f.can_id & CAN_SFF_MASK;
  if (id <= kEmcyBase || id > kEmcyBase + 127 || f.can_dlc != 8) return std::nullopt;
  Emergency e;
  e.node_id = static_cast<uint8_t>(id - kEmcyBase);
  e.error_code = static_cast<uint16_t>(get_le(f.data, 2));
  e.error_register = f.data[2];
  return e;
}

uint8_t register_for(uint16_t code)
{
  if (code == kNoError) return 0;
  switch (code >> 12) {
    case 0x2: return kRegGeneric | kRegCurrent;
    case 0x3: return kRegGeneric | kRegVoltage;
    case 0x4: return kRegGeneric | kRegTemperature;
    case 0x8: return kRegGeneric | (code >= 0x8600 ? kRegProfile : kRegCommunication);
    default: return kRegGeneric;
  }
}

std::string describe(uint16_t code)
{
  const char* t = "device error";
  switch (code) {
    case kNoError: t = "error reset / no error"; break;
    case kGeneric: t = "generic error"; break;
    case kContinuousOverCurrent: t = "continuous over-current"; break;
    case kOverVoltage: t = "DC link over-voltage"; break;
    case kDriveTemperature: t = "drive over-temperature"; break;
    case kHeartbeatError: t = "heartbeat consumer: producer lost"; break;
    case kRecoveredFromBusOff: t = "recovered from bus-off"; break;
    case kFollowingError: t = "following error"; break;
    default: break;
  }
  char buf[80];
  std::snprintf(buf, sizeof buf, "EMCY 0x%04X %s", code, t);
  return buf;
}

}  // namespace rgnav::can::canopen::emcy
