// Device side of the PDOs (CiA 301 §7.2.2): RPDOs write mapped objects into the object
// dictionary, TPDOs pack mapped objects into frames on SYNC (transmission types 1-240) or on
// change / event timer (254, 255). Also the SDO-write checks that keep the PDO configuration
// consistent: mapping only while the PDO is invalid, mapped objects must exist, be mappable in
// that direction, and fit in 8 bytes.
#pragma once

#include <linux/can.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "emulator/object_dictionary.h"

namespace rgnav::can::emulator {

class DevicePdos
{
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const can_frame&)>;
  static constexpr int kCount = 4;

  explicit DevicePdos(ObjectDictionary* od) : od_(od) {}

  // SDO abort code for a write to 0x1400-0x1403, 0x1600-0x1603, 0x1800-0x1803, 0x1A00-0x1A03
  // (0 = fine, also for any other object).
  uint32_t check_write(uint16_t index, uint8_t sub, uint32_t value) const;

  // True if `f` is an enabled RPDO of this device (it is then applied, or buffered until the
  // next SYNC for synchronous transmission types).
  bool on_rpdo(const can_frame& f);
  // Applies buffered synchronous RPDOs, then sends the synchronous TPDOs that are due.
  void on_sync(const Sink& send);
  // Event-driven TPDOs (types 254/255): on change (respecting the inhibit time) or when the
  // event timer elapses.
  void on_tick(Clock::time_point now, const Sink& send);
  // Forgets counters, buffers and change history (NMT reset / leaving operational).
  void reset();

 private:
  struct Mapped
  {
    uint16_t index;
    uint8_t sub;
    uint8_t bytes;
  };
  std::vector<Mapped> mapping(uint16_t map_index) const;
  std::optional<can_frame> pack_tpdo(int i) const;
  uint32_t check_mapping_entry(uint16_t index, uint32_t entry, bool receive) const;

  ObjectDictionary* od_;
  std::array<int, kCount> sync_count_{};
  std::array<std::optional<can_frame>, kCount> rpdo_buffer_{};
  std::array<std::optional<can_frame>, kCount> last_sent_{};
  std::array<Clock::time_point, kCount> last_sent_time_{};
};

}  // namespace rgnav::can::emulator
