// CiA 301 (CANopen application layer) basics shared by the master and the drive emulator:
// the predefined connection set (COB-IDs), NMT commands and states, heartbeat, SYNC, and
// little-endian packing of object values. See CiA 301 v4.2 §7.2 (COB-IDs), §7.2.8 (NMT).
#pragma once

#include <linux/can.h>

#include <cstdint>
#include <optional>
#include <string>

namespace rgnav::can::canopen {

// Function codes of the predefined connection set (COB-ID = function code + node id).
constexpr canid_t kNmt = 0x000;
constexpr canid_t kSync = 0x080;
constexpr canid_t kEmcyBase = 0x080;
constexpr canid_t kTpdo1 = 0x180, kRpdo1 = 0x200, kTpdo2 = 0x280, kRpdo2 = 0x300;
constexpr canid_t kTpdo3 = 0x380, kRpdo3 = 0x400, kTpdo4 = 0x480, kRpdo4 = 0x500;
constexpr canid_t kSdoTx = 0x580;  // server -> client
constexpr canid_t kSdoRx = 0x600;  // client -> server
constexpr canid_t kHeartbeat = 0x700;
// COB-ID entries of 0x14xx/0x18xx: bit 31 set = PDO not valid.
constexpr uint32_t kCobIdInvalid = 0x80000000u;

constexpr bool valid_node_id(int id) { return id >= 1 && id <= 127; }

enum class NmtCommand : uint8_t
{
  kStart = 0x01,
  kStop = 0x02,
  kEnterPreOperational = 0x80,
  kResetNode = 0x81,
  kResetCommunication = 0x82,
};

// States as carried in heartbeat byte 0.
enum class NmtState : uint8_t
{
  kBootUp = 0x00,  // boot-up message (initialising done)
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
};

const char* to_string(NmtState s);
const char* to_string(NmtCommand c);
// nullopt for a byte that is no NMT state.
std::optional<NmtState> nmt_state_from_byte(uint8_t b);

// node_id 0 addresses every node.
can_frame make_nmt(NmtCommand cmd, uint8_t node_id);
can_frame make_heartbeat(uint8_t node_id, NmtState state);
can_frame make_sync();

// Little-endian object values as they travel in SDO and PDO payloads.
inline uint32_t get_le(const uint8_t* p, int bytes)
{
  uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
inline void put_le(uint8_t* p, uint32_t v, int bytes)
{
  for (int i = 0; i < bytes; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

}  // namespace rgnav::can::canopen
