// SDO (service data object) messages, CiA 301 §7.2.4: the initiate/expedited transfers the
// master uses to configure drives (values up to 4 bytes) and the abort transfer. Segmented
// and block transfers are not spoken: a server answers them with an abort, a client never
// starts one, and an upload answered with "segmented follows" is an error to the client.
#pragma once

#include <linux/can.h>

#include <cstdint>
#include <string>

namespace rgnav::can::canopen::sdo {

// Abort codes, CiA 301 Table 22.
enum AbortCode : uint32_t
{
  kToggleBit = 0x05030000,
  kTimeout = 0x05040000,
  kBadCommand = 0x05040001,
  kOutOfMemory = 0x05040005,
  kUnsupportedAccess = 0x06010000,
  kWriteOnly = 0x06010001,
  kReadOnly = 0x06010002,
  kNoObject = 0x06020000,
  kNotMappable = 0x06040041,
  kPdoTooLong = 0x06040042,
  kIncompatible = 0x06040043,
  kHardwareError = 0x06060000,
  kLengthMismatch = 0x06070010,
  kLengthTooHigh = 0x06070012,
  kLengthTooLow = 0x06070013,
  kNoSubIndex = 0x06090011,
  kInvalidValue = 0x06090030,
  kValueTooHigh = 0x06090031,
  kValueTooLow = 0x06090032,
  kGeneralError = 0x08000000,
  kCannotTransfer = 0x08000020,
  kLocalControl = 0x08000021,
  kDeviceState = 0x08000022,
};
std::string abort_text(uint32_t code);

struct Message
{
  enum class Type
  {
    kDownloadRequest,   // client writes `value` (size bytes, 0 = unspecified)
    kDownloadResponse,  // server confirms a write
    kUploadRequest,     // client reads
    kUploadResponse,    // server returns `value` (expedited)
    kAbort,             // either side; `abort_code` says why
    kUnsupported,       // segmented/block transfer or garbage
  };
  Type type = Type::kUnsupported;
  uint16_t index = 0;
  uint8_t subindex = 0;
  uint32_t value = 0;
  uint8_t size = 0;  // bytes of value, 1..4; 0 = not indicated
  uint32_t abort_code = 0;
};

// Parses the 8-byte payload of an SDO frame (either direction).
Message parse(const can_frame& f);

// Frames; `cob_id` is 0x600 + node for client->server, 0x580 + node for server->client.
can_frame download_request(uint8_t node_id, uint16_t index, uint8_t sub, uint32_t value, uint8_t size);
can_frame upload_request(uint8_t node_id, uint16_t index, uint8_t sub);
can_frame download_response(uint8_t node_id, uint16_t index, uint8_t sub);
can_frame upload_response(uint8_t node_id, uint16_t index, uint8_t sub, uint32_t value, uint8_t size);
can_frame abort(canid_t cob_id, uint16_t index, uint8_t sub, uint32_t code);

}  // namespace rgnav::can::canopen::sdo
