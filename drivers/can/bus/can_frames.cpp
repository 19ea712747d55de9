#include "bus/can_frames.h"

#include <cstdio>
#include <cstring>

namespace rgnav::can {

can_frame make_frame(canid_t id, std::initializer_list<uint8_t> data)
{
  can_frame f;
  std::memset(&f, 0, sizeof f);
  f.can_id = id & CAN_SFF_MASK;
  size_t i = 0;
  for (uint8_t b : data) {
    if (i == CAN_MAX_DLEN) break;
    f.data[i++] = b;
  }
  f.can_dlc = static_cast<uint8_t>(i);
  return f;
}

can_frame make_frame(canid_t id, const uint8_t* data, uint8_t dlc)
{
  can_frame f;
  std::memset(&f, 0, sizeof f);
  f.can_id = id & CAN_SFF_MASK;
  f.can_dlc = dlc > CAN_MAX_DLEN ? CAN_MAX_DLEN : dlc;
  if (f.can_dlc > 0) std::memcpy(f.data, data, f.can_dlc);
  return f;
}

bool is_error_frame(const can_frame& f) { return (f.can_id & CAN_ERR_FLAG) != 0; }
bool is_extended(const can_frame& f) { return (f.can_id & CAN_EFF_FLAG) != 0; }

canid_t frame_id(const can_frame& f)
{
  return is_extended(f) ? (f.can_id & CAN_EFF_MASK) : (f.can_id & CAN_SFF_MASK);
}

bool passes_filters(const can_frame& f, const std::vector<can_filter>& filters)
{
  for (const auto& flt : filters) {
    const bool inverted = (flt.can_id & CAN_INV_FILTER) != 0;
    const canid_t id = flt.can_id & ~CAN_INV_FILTER;
    const bool match = (f.can_id & flt.can_mask) == (id & flt.can_mask);
    if (match != inverted) return true;
  }
  return false;
}

bool passes_error_mask(const can_frame& f, can_err_mask_t mask)
{
  return (f.can_id & CAN_ERR_MASK & mask) != 0;
}

ErrorFrameInfo classify_error(const can_frame& f)
{
  ErrorFrameInfo info;
  if (!is_error_frame(f)) return info;
  const canid_t cls = f.can_id & CAN_ERR_MASK;
  info.bus_off = (cls & CAN_ERR_BUSOFF) != 0;
  info.restarted = (cls & CAN_ERR_RESTARTED) != 0;
  if (cls & CAN_ERR_CRTL) {
    const uint8_t d = f.data[1];
    info.error_passive = (d & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0;
    info.warning = (d & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0;
  }
  std::string t;
  auto add = [&t](const char* s) { t += t.empty() ? s : std::string(", ") + s; };
  if (cls & CAN_ERR_TX_TIMEOUT) add("tx timeout");
  if (cls & CAN_ERR_LOSTARB) add("lost arbitration");
  if (cls & CAN_ERR_CRTL) add(info.error_passive ? "controller error-passive" : info.warning ? "controller warning" : "controller problem");
  if (cls & CAN_ERR_PROT) add("protocol violation");
  if (cls & CAN_ERR_TRX) add("transceiver problem");
  if (cls & CAN_ERR_ACK) add("no ack");
  if (cls & CAN_ERR_BUSOFF) add("bus-off");
  if (cls & CAN_ERR_BUSERROR) add("bus error");
  if (cls & CAN_ERR_RESTARTED) add("controller restarted");
  info.text = t.empty() ? "error frame" : t;
  return info;
}

can_frame make_error_frame(can_err_mask_t error_class, uint8_t controller_detail)
{
  can_frame f;
  std::memset(&f, 0, sizeof f);
  f.can_id = CAN_ERR_FLAG | (error_class & CAN_ERR_MASK);
  f.can_dlc = CAN_ERR_DLC;
  f.data[1] = controller_detail;
  return f;
}

std::string to_string(const can_frame& f)
{
  char buf[64];
  int n = is_extended(f) || is_error_frame(f)
              ? std::snprintf(buf, sizeof buf, "%08X#", f.can_id & CAN_EFF_MASK)
              : std::snprintf(buf, sizeof buf, "%03X#", f.can_id & CAN_SFF_MASK);
  for (int i = 0; i < f.can_dlc && i < CAN_MAX_DLEN; ++i)
    n += std::snprintf(buf + n, sizeof buf - static_cast<size_t>(n), "%02X", f.data[i]);
  return buf;
}

}  // namespace rgnav::can
