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
constexpr uint32_t kToggleBit = 0x05030000;
constexpr uint32_t kTimeout = 0x05040000;
constexpr uint32_t kBadCommand = 0x05040001;
constexpr uint32_t kOutOfMemory = 0x05040005;
constexpr uint32_t kUnsupportedAccess = 0x06010000;
constexpr uint32_t kWriteOnly = 0x06010001;
constexpr uint32_t kReadOnly = 0x06010002;
constexpr uint32_t kNoObject = 0x06020000;
constexpr uint32_t kNotMappable = 0x06040041;
constexpr uint32_t kPdoTooLong = 0x06040042;
constexpr uint32_t kIncompatible = 0x06040043;
constexpr uint32_t kHardwareError = 0x06060000;
constexpr uint32_t kLengthMismatch = 0x06070010;
constexpr uint32_t kLengthTooHigh = 0x06070012;
constexpr uint32_t kLengthTooLow = 0x06070013;
constexpr uint32_t kNoSubIndex = 0x06090011;
constexpr uint32_t kInvalidValue = 0x06090030;
constexpr uint32_t kValueTooHigh = 0x06090031;
constexpr uint32_t kValueTooLow = 0x06090032;
constexpr uint32_t kGeneralError = 0x08000000;
constexpr uint32_t kCannotTransfer = 0x08000020;
constexpr uint32_t kLocalControl = 0x08000021;
constexpr uint32_t kDeviceState = 0x08000022;
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
