// Wire format of the user-space virtual CAN bus (vcan_broker.h). The broker listens on a Unix
// SOCK_SEQPACKET socket; every packet a client sends is either
//   - exactly one `struct can_frame` (16 bytes): a data frame to put on the bus, or
//   - one VcanControl (64 bytes): a request to the broker (name this client, test hooks).
// The broker sends clients only can_frames (data frames of the others, and error frames).
// SEQPACKET keeps packet boundaries, so there is no framing layer to get wrong.
#pragma once

#include <linux/can.h>

#include <cstdint>
#include <string>

namespace rgnav::can::vcan {

constexpr uint32_t kControlMagic = 0x4C544356;  // "VCTL" little-endian

enum class ControlOp : uint32_t
{
  kHello = 1,        // name = this client's name (for hooks that address clients by name)
  kDropFrames = 2,   // drop the next arg2 frames whose id matches (arg0 & arg1); arg2 = 0xFFFFFFFF: until cleared
  kClearDrops = 3,
  kInjectError = 4,  // error frame with class arg0 (CAN_ERR_*) and data[1] = arg1 to every client
  kBusOff = 5,       // client `name` goes bus-off for arg0 ms (error frames BUSOFF then RESTARTED)
  kDisconnect = 6,   // the broker closes client `name`'s connection
};

struct VcanControl
{
  uint32_t magic = kControlMagic;
  uint32_t op = 0;
  uint32_t arg0 = 0;
  uint32_t arg1 = 0;
  uint32_t arg2 = 0;
  char name[44] = {0};
};
static_assert(sizeof(VcanControl) == 64, "VcanControl is a fixed 64-byte packet");
static_assert(sizeof(can_frame) == 16, "the bus carries classic CAN frames");

// "/tmp/rgnav-vcan-<bus>.sock"; a path starting with '@' names the abstract namespace.
std::string default_socket_path(const std::string& bus_name);

}  // namespace rgnav::can::vcan
