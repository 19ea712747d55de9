// The object dictionary of an emulated CANopen device: typed entries (1, 2 or 4 bytes,
// signed or not) with CiA 301 access rights, PDO mappability and defaults, read and written by
// the SDO server (with abort codes) and by the device application (without access checks).
// Entries are declared in code (drive_object_dictionary.cpp) after the EDS of a CiA 402 drive
// in shared/data/canopen/cia402_slave.eds; a test checks the two agree.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <utility>

namespace rgnav::can::emulator {

enum class Access : uint8_t
{
  kConst,  // read only, never changes
  kRo,     // read only, the device updates it
  kRw,     // read/write
  kWo,     // write only
};

struct OdEntry
{
  uint8_t size = 4;  // bytes: 1, 2 or 4
  bool is_signed = false;
  Access access = Access::kRw;
  bool pdo_mappable = false;
  uint32_t default_value = 0;
  uint32_t value = 0;
};

class ObjectDictionary
{
 public:
  // Extra checks on SDO writes beyond size and access (value ranges, device state); returns
  // an SDO abort code, 0 to accept.
  using WriteCheck = std::function<uint32_t(uint16_t index, uint8_t sub, uint32_t value)>;
  // Called after every accepted write (SDO or PDO).
  using WriteHook = std::function<void(uint16_t index, uint8_t sub)>;

  void add(uint16_t index, uint8_t sub, uint8_t size, bool is_signed, Access access, bool pdo_mappable,
           uint32_t default_value);
  const OdEntry* find(uint16_t index, uint8_t sub) const;
  bool has_object(uint16_t index) const;

  void set_write_check(WriteCheck check) { check_ = std::move(check); }
  void set_write_hook(WriteHook hook) { hook_ = std::move(hook); }

  // SDO server access; return 0 or an SDO abort code.
  uint32_t sdo_read(uint16_t index, uint8_t sub, uint32_t* value, uint8_t* size) const;
  // size 0 = "not indicated" (accepted for any entry size).
  uint32_t sdo_write(uint16_t index, uint8_t sub, uint32_t value, uint8_t size);
  // RPDO write of a mapped entry (mapping was validated when it was configured).
  void pdo_write(uint16_t index, uint8_t sub, uint32_t value);

  // Device-application access, no access checks. get() of a missing entry is 0.
  uint32_t get(uint16_t index, uint8_t sub = 0) const;
  int32_t get_signed(uint16_t index, uint8_t sub = 0) const;
  void set(uint16_t index, uint8_t sub, uint32_t value);
  void set(uint16_t index, uint32_t value) { set(index, 0, value); }

  // Restores the defaults of every entry with lo <= index <= hi (NMT reset communication:
  // 0x1000-0x1FFF; reset node: everything).
  void reset(uint16_t lo, uint16_t hi);

  const std::map<std::pair<uint16_t, uint8_t>, OdEntry>& entries() const { return entries_; }

 private:
  std::map<std::pair<uint16_t, uint8_t>, OdEntry> entries_;
  WriteCheck check_;
  WriteHook hook_;
};

}  // namespace rgnav::can::emulator
