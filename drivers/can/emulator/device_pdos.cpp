#include "emulator/device_pdos.h"

#include <cstring>

#include "canopen/protocol.h"
#include "canopen/sdo.h"

namespace rgnav::can::emulator {

namespace sdo = canopen::sdo;
using canopen::kCobIdInvalid;

namespace {

bool pdo_valid(uint32_t cob_id) { return (cob_id & kCobIdInvalid) == 0; }
bool is_sync_type(uint32_t t) { return t >= 1 && t <= 240; }

}  // namespace

uint32_t DevicePdos::check_mapping_entry(uint16_t index, uint32_t entry, bool receive) const
{
  if (entry == 0) return 0;  // unused entry
  const auto obj = static_cast<uint16_t>(entry >> 16);
  const auto sub = static_cast<uint8_t>(entry >> 8);
  const auto bits = static_cast<uint8_t>(entry);
  const OdEntry* e = od_->find(obj, sub);
  if (!e) return sdo::kNoObject;
  if (!e->pdo_mappable) return sdo::kNotMappable;
  if (receive && (e->access == Access::kRo || e->access == Access::kConst)) return sdo::kNotMappable;
  if (!receive && e->access == Access::kWo) return sdo::kNotMappable;
  if (bits != e->size * 8) return sdo::kLengthMismatch;
  (void)index;
  return 0;
}

uint32_t DevicePdos::check_write(uint16_t index, uint8_t sub, uint32_t value) const
{
  const bool rx_comm = index >= 0x1400 && index < 0x1400 + kCount;
  const bool tx_comm = index >= 0x1800 && index < 0x1800 + kCount;
  const bool rx_map = index >= 0x1600 && index < 0x1600 + kCount;
  const bool tx_map = index >= 0x1A00 && index < 0x1A00 + kCount;
  if (rx_comm || tx_comm) {
    const uint32_t cob_now = od_->get(index, 1);
    if (sub == 1) {
      const canid_t id = value & CAN_SFF_MASK;
      // A valid COB-ID must be a usable 11-bit id; changing it requires invalidating first.
      if (pdo_valid(value) && (value & 0x20000000u)) return sdo::kInvalidValue;  // 29-bit ids not supported
      if (pdo_valid(value) && (id == 0 || id > 0x7FF)) return sdo::kInvalidValue;
      if (pdo_valid(value) && pdo_valid(cob_now) && (cob_now & CAN_SFF_MASK) != id) return sdo::kInvalidValue;
      return 0;
    }
    if (sub == 2) {
      if ((value > 240 && value < 252) || value == 252 || value == 253) return sdo::kInvalidValue;
      return 0;
    }
    if (sub == 3 && pdo_valid(cob_now)) return sdo::kDeviceState;  // inhibit time only while invalid
    return 0;
  }
  if (rx_map || tx_map) {
    const uint16_t comm = static_cast<uint16_t>(index - 0x200);
    if (pdo_valid(od_->get(comm, 1))) return sdo::kDeviceState;
    if (sub == 0) {
      if (value > 3) return sdo::kValueTooHigh;
      unsigned bits = 0;
      for (uint8_t s = 1; s <= value; ++s) {
        const uint32_t entry = od_->get(index, s);
        if (const uint32_t abort = check_mapping_entry(index, entry, rx_map); abort) return abort;
        bits += entry & 0xFF;
      }
      return bits > 64 ? sdo::kPdoTooLong : 0;
    }
    if (od_->get(index, 0) != 0) return sdo::kDeviceState;  // entries change only while sub0 = 0
    return check_mapping_entry(index, value, rx_map);
  }
  return 0;
}

std::vector<DevicePdos::Mapped> DevicePdos::mapping(uint16_t map_index) const
{
  std::vector<Mapped> m;
  const uint32_t n = od_->get(map_index, 0);
  for (uint8_t s = 1; s <= n && s <= 3; ++s) {
    const uint32_t entry = od_->get(map_index, s);
    if (entry == 0) continue;
    m.push_back({static_cast<uint16_t>(entry >> 16), static_cast<uint8_t>(entry >> 8),
                 static_cast<uint8_t>((entry & 0xFF) / 8)});
  }
  return m;
}

bool DevicePdos::on_rpdo(const can_frame& f)
{
  for (int i = 0; i < kCount; ++i) {
    const uint32_t cob = od_->get(static_cast<uint16_t>(0x1400 + i), 1);
    if (!pdo_valid(cob) || (cob & CAN_SFF_MASK) != (f.can_id & CAN_SFF_MASK)) continue;
    if (is_sync_type(od_->get(static_cast<uint16_t>(0x1400 + i), 2)) || od_->get(static_cast<uint16_t>(0x1400 + i), 2) == 0) {
      rpdo_buffer_[static_cast<size_t>(i)] = f;  // applied at the next SYNC
      return true;
    }
    size_t off = 0;
    const auto map = mapping(static_cast<uint16_t>(0x1600 + i));
    size_t need = 0;
    for (const auto& m : map) need += m.bytes;
    if (f.can_dlc < need) return true;  // too short: not processed (CiA 301 would send EMCY 0x8210)
    for (const auto& m : map) {
      od_->pdo_write(m.index, m.sub, canopen::get_le(f.data + off, m.bytes));
      off += m.bytes;
    }
    return true;
  }
  return false;
}

std::optional<can_frame> DevicePdos::pack_tpdo(int i) const
{
  const uint32_t cob = od_->get(static_cast<uint16_t>(0x1800 + i), 1);
  if (!pdo_valid(cob)) return std::nullopt;
  can_frame f;
  std::memset(&f, 0, sizeof f);
  f.can_id = cob & CAN_SFF_MASK;
  size_t off = 0;
  for (const auto& m : mapping(static_cast<uint16_t>(0x1A00 + i))) {
    canopen::put_le(f.data + off, od_->get(m.index, m.sub), m.bytes);
    off += m.bytes;
  }
  f.can_dlc = static_cast<uint8_t>(off);
  return f;
}

void DevicePdos::on_sync(const Sink& send)
{
  for (int i = 0; i < kCount; ++i) {
    auto& buf = rpdo_buffer_[static_cast<size_t>(i)];
    if (!buf) continue;
    const can_frame f = *buf;
    buf.reset();
    size_t off = 0;
    const auto map = mapping(static_cast<uint16_t>(0x1600 + i));
    size_t need = 0;
    for (const auto& m : map) need += m.bytes;
    if (f.can_dlc < need) continue;
    for (const auto& m : map) {
      od_->pdo_write(m.index, m.sub, canopen::get_le(f.data + off, m.bytes));
      off += m.bytes;
    }
  }
  for (int i = 0; i < kCount; ++i) {
    const uint32_t type = od_->get(static_cast<uint16_t>(0x1800 + i), 2);
    if (!is_sync_type(type)) continue;
    if (++sync_count_[static_cast<size_t>(i)] < static_cast<int>(type)) continue;
    sync_count_[static_cast<size_t>(i)] = 0;
    if (auto f = pack_tpdo(i)) send(*f);
  }
}

void DevicePdos::on_tick(Clock::time_point now, const Sink& send)
{
  for (int i = 0; i < kCount; ++i) {
    const auto idx = static_cast<uint16_t>(0x1800 + i);
    const uint32_t type = od_->get(idx, 2);
    if (type != 254 && type != 255) continue;
    auto f = pack_tpdo(i);
    if (!f) continue;
    const auto k = static_cast<size_t>(i);
    const auto inhibit = std::chrono::microseconds(100 * od_->get(idx, 3));
    const auto event = std::chrono::milliseconds(od_->get(idx, 5));
    const bool changed = !last_sent_[k] || last_sent_[k]->can_dlc != f->can_dlc ||
                         std::memcmp(last_sent_[k]->data, f->data, f->can_dlc) != 0;
    const bool inhibited = last_sent_[k] && now - last_sent_time_[k] < inhibit;
    const bool timer_due = event.count() > 0 && (!last_sent_[k] || now - last_sent_time_[k] >= event);
    if ((changed && !inhibited) || timer_due) {
      send(*f);
      last_sent_[k] = f;
      last_sent_time_[k] = now;
    }
  }
}

void DevicePdos::reset()
{
  sync_count_.fill(0);
  for (auto& b : rpdo_buffer_) b.reset();
  for (auto& s : last_sent_) s.reset();
}

}  // namespace rgnav::can::emulator
