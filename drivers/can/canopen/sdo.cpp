#include "canopen/sdo.h"

#include <cstdio>
#include <cstring>

#include "canopen/protocol.h"

namespace rgnav::can::canopen::sdo {

namespace {

can_frame frame(canid_t id, uint8_t command, uint16_t index, uint8_t sub, uint32_t payload)
{
  can_frame f;
  std::memset(&f, 0, sizeof f);
  f.can_id = id;
  f.can_dlc = 8;
  f.data[0] = command;
  put_le(f.data + 1, index, 2);
  f.data[3] = sub;
  put_le(f.data + 4, payload, 4);
  return f;
}

uint32_t masked(uint32_t value, uint8_t size) { return size >= 4 ? value : value & ((1u << (8 * size)) - 1); }

}  // namespace

std::string abort_text(uint32_t code)
{
  const char* t = nullptr;
  switch (code) {
    case kToggleBit: t = "toggle bit not alternated"; break;
    case kTimeout: t = "SDO protocol timed out"; break;
    case kBadCommand: t = "command specifier not valid or unknown"; break;
    case kOutOfMemory: t = "out of memory"; break;
    case kUnsupportedAccess: t = "unsupported access to an object"; break;
    case kWriteOnly: t = "attempt to read a write-only object"; break;
    case kReadOnly: t = "attempt to write a read-only object"; break;
    case kNoObject: t = "object does not exist in the object dictionary"; break;
    case kNotMappable: t = "object cannot be mapped to the PDO"; break;
    case kPdoTooLong: t = "number and length of mapped objects exceed PDO length"; break;
    case kIncompatible: t = "general parameter incompatibility"; break;
    case kHardwareError: t = "access failed due to a hardware error"; break;
    case kLengthMismatch: t = "data type does not match, length of service parameter does not match"; break;
    case kLengthTooHigh: t = "data type does not match, length too high"; break;
    case kLengthTooLow: t = "data type does not match, length too low"; break;
    case kNoSubIndex: t = "sub-index does not exist"; break;
    case kInvalidValue: t = "invalid value for parameter"; break;
    case kValueTooHigh: t = "value of parameter written too high"; break;
    case kValueTooLow: t = "value of parameter written too low"; break;
    case kGeneralError: t = "general error"; break;
    case kCannotTransfer: t = "data cannot be transferred or stored to the application"; break;
    case kLocalControl: t = "data cannot be transferred because of local control"; break;
    case kDeviceState: t = "data cannot be transferred because of the present device state"; break;
    default: break;
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "0x%08X (%s)", code, t ? t : "unknown abort code");
  return buf;
}

Message parse(const can_frame& f)
{
  Message m;
  if (f.can_dlc != 8) return m;  // SDO frames always carry 8 bytes
  const uint8_t cmd = f.data[0];
  m.index = static_cast<uint16_t>(get_le(f.data + 1, 2));
  m.subindex = f.data[3];
  const uint32_t payload = get_le(f.data + 4, 4);
  const uint8_t cs = cmd >> 5;
  const bool expedited = cmd & 0x02;
  const bool size_indicated = cmd & 0x01;
  const uint8_t size = size_indicated ? static_cast<uint8_t>(4 - ((cmd >> 2) & 0x03)) : 0;
  const canid_t base = f.can_id & 0x780;
  if (cmd == 0x80) {
    m.type = Message::Type::kAbort;
    m.abort_code = payload;
    return m;
  }
  if (base == kSdoRx) {  // client -> server
    if (cs == 1 && expedited) {
      m.type = Message::Type::kDownloadRequest;
      m.size = size;
      m.value = masked(payload, size ? size : 4);
    } else if (cs == 2) {
      m.type = Message::Type::kUploadRequest;
    }
  } else if (base == kSdoTx) {  // server -> client
    if (cs == 3) {
      m.type = Message::Type::kDownloadResponse;
    } else if (cs == 2 && expedited) {
      m.type = Message::Type::kUploadResponse;
      m.size = size;
      m.value = masked(payload, size ? size : 4);
    }
  }
  return m;
}

can_frame download_request(uint8_t node_id, uint16_t index, uint8_t sub, uint32_t value, uint8_t size)
{
  if (size < 1 || size > 4) size = 4;
  const auto cmd = static_cast<uint8_t>(0x20 | ((4 - size) << 2) | 0x03);
  return frame(kSdoRx + node_id, cmd, index, sub, masked(value, size));
}

can_frame upload_request(uint8_t node_id, uint16_t index, uint8_t sub)
{
  return frame(kSdoRx + node_id, 0x40, index, sub, 0);
}

can_frame download_response(uint8_t node_id, uint16_t index, uint8_t sub)
{
  return frame(kSdoTx + node_id, 0x60, index, sub, 0);
}

can_frame upload_response(uint8_t node_id, uint16_t index, uint8_t sub, uint32_t value, uint8_t size)
{
  if (size < 1 || size > 4) size = 4;
  const auto cmd = static_cast<uint8_t>(0x40 | ((4 - size) << 2) | 0x03);
  return frame(kSdoTx + node_id, cmd, index, sub, masked(value, size));
}

can_frame abort(canid_t cob_id, uint16_t index, uint8_t sub, uint32_t code)
{
  return frame(cob_id, 0x80, index, sub, code);
}

}  // namespace rgnav::can::canopen::sdo
