// LMS 2xx telegram framing (serial, RS-232/RS-422, 8N1):
//
//   STX(0x02) | ADR | LEN (u16 LE) | CMD | DATA ... | [STATUS] | CRC (u16 LE)
//
// ADR is the receiver: 0x00 (the LMS, factory address) for host→LMS, 0x80 (host bit | LMS
// address) for LMS→host. LEN counts CMD + DATA (+ STATUS): everything between LEN and CRC.
// Replies from the LMS carry command | 0x80 and end with a status byte. Before a reply the
// LMS sends a lone ACK byte (0x06) for an accepted request or NAK (0x15) for a broken one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace rgnav::drivers::sick {

constexpr uint8_t kStx = 0x02;
constexpr uint8_t kAck = 0x06;
constexpr uint8_t kNak = 0x15;
constexpr uint8_t kAddressLms = 0x00;   // requests to an LMS at the factory address 0
constexpr uint8_t kAddressHost = 0x80;  // replies from that LMS
constexpr size_t kHeaderSize = 4;       // STX, ADR, LEN (2)
constexpr size_t kCrcSize = 2;
// Longest payload an LMS 2xx sends: 401 values of the 0.25° variant as 0xB0 (806 bytes),
// rounded up to the 812 the telegram listing gives as the receive buffer size.
constexpr size_t kMaxPayload = 812;

// Command codes (host → LMS).
namespace cmd {
constexpr uint8_t kReset = 0x10;             // initialise and reset
constexpr uint8_t kSwitchMode = 0x20;        // operating mode / baud rate
constexpr uint8_t kRequestValues = 0x30;     // measured values on request
constexpr uint8_t kRequestStatus = 0x31;
constexpr uint8_t kRequestType = 0x3A;
constexpr uint8_t kSetVariant = 0x3B;        // scan angle and angular resolution
constexpr uint8_t kRequestConfig = 0x74;
constexpr uint8_t kSetConfig = 0x77;
}  // namespace cmd

// Reply codes (LMS → host): request | 0x80, plus the unsolicited ones.
namespace reply {
constexpr uint8_t kPowerOn = 0x90;           // sent after power-up / reset completes
constexpr uint8_t kResetAck = 0x91;
constexpr uint8_t kIncorrectCommand = 0x92;  // not-acknowledge of an unknown request
constexpr uint8_t kSwitchMode = 0xA0;
constexpr uint8_t kMeasuredValues = 0xB0;
constexpr uint8_t kStatus = 0xB1;
constexpr uint8_t kType = 0xBA;
constexpr uint8_t kVariant = 0xBB;
constexpr uint8_t kConfig = 0xF4;
constexpr uint8_t kSetConfig = 0xF7;
}  // namespace reply

constexpr uint8_t reply_code(uint8_t request) { return static_cast<uint8_t>(request | 0x80); }

// One framed telegram: ADR and the payload CMD + DATA (+ STATUS in replies).
struct Telegram
{
  uint8_t address = kAddressLms;
  std::vector<uint8_t> payload;

  uint8_t command() const { return payload.empty() ? 0 : payload[0]; }
  bool operator==(const Telegram& o) const { return address == o.address && payload == o.payload; }
};

// A reply split into its parts (payload = command, data..., status).
struct Reply
{
  uint8_t command = 0;
  std::vector<uint8_t> data;
  uint8_t status = 0;
};

// The status byte's low three bits: 0 no error, 1 info, 2 warning, 3 error, 4 fatal error.
constexpr int status_error_class(uint8_t status) { return status & 0x07; }
constexpr bool status_is_error(uint8_t status) { return status_error_class(status) >= 3; }

// Frames a payload; throws std::length_error when it is empty or longer than kMaxPayload.
std::vector<uint8_t> frame(uint8_t address, const std::vector<uint8_t>& payload);
std::vector<uint8_t> frame(const Telegram& t);
// Parses exactly one complete frame (tests, tools); nullopt on any framing or CRC error.
std::optional<Telegram> unframe(const uint8_t* bytes, size_t size);
// A reply needs at least a command and a status byte.
std::optional<Reply> as_reply(const Telegram& t);
Telegram make_reply(uint8_t command, const std::vector<uint8_t>& data, uint8_t status);

// Bytes on the wire for a payload of n bytes.
constexpr size_t framed_size(size_t payload_size) { return kHeaderSize + payload_size + kCrcSize; }

// Little-endian helpers used by every encoder.
inline void put_u16(std::vector<uint8_t>* out, uint16_t v)
{
  out->push_back(static_cast<uint8_t>(v & 0xFF));
  out->push_back(static_cast<uint8_t>(v >> 8));
}
inline uint16_t get_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }

}  // namespace rgnav::drivers::sick
