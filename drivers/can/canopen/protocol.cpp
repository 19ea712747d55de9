#include "canopen/protocol.h"

#include "bus/can_frames.h"

namespace rgnav::can::canopen {

const char* to_string(NmtState s)
{
  switch (s) {
    case NmtState::kBootUp: return "boot-up";
    case NmtState::kStopped: return "stopped";
    case NmtState::kOperational: return "operational";
    case NmtState::kPreOperational: return "pre-operational";
  }
  return "?";
}

const char* to_string(NmtCommand c)
{
  switch (c) {
    case NmtCommand::kStart: return "start";
    case NmtCommand::kStop: return "stop";
    case NmtCommand::kEnterPreOperational: return "enter pre-operational";
    case NmtCommand::kResetNode: return "reset node";
    case NmtCommand::kResetCommunication: return "reset communication";
  }
  return "?";
}

std::optional<NmtState> nmt_state_from_byte(uint8_t b)
{
  switch (b & 0x7F) {  // bit 7 is the node-guarding toggle bit, never set in heartbeats
    case 0x00: return NmtState::kBootUp;
    case 0x04: return NmtState::kStopped;
    case 0x05: return NmtState::kOperational;
    case 0x7F: return NmtState::kPreOperational;
    default: return std::nullopt;
  }
}

can_frame make_nmt(NmtCommand cmd, uint8_t node_id)
{
  return make_frame(kNmt, {static_cast<uint8_t>(cmd), node_id});
}

can_frame make_heartbeat(uint8_t node_id, NmtState state)
{
  return make_frame(kHeartbeat + node_id, {static_cast<uint8_t>(state)});
}

can_frame make_sync() { return make_frame(kSync, {}); }

}  // namespace rgnav::can::canopen
