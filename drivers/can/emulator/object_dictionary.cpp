#include "emulator/object_dictionary.h"

#include "canopen/sdo.h"

namespace rgnav::can::emulator {

namespace sdo = canopen::sdo;

namespace {

uint32_t truncate(uint32_t value, uint8_t size) { return size >= 4 ? value : value & ((1u << (8 * size)) - 1); }

}  // namespace

void ObjectDictionary::add(uint16_t index, uint8_t sub, uint8_t size, bool is_signed, Access access, bool pdo_mappable,
                           uint32_t default_value)
{
  OdEntry e;
  e.size = size;
  e.is_signed = is_signed;
  e.access = access;
  e.pdo_mappable = pdo_mappable;
  e.default_value = truncate(default_value, size);
  e.value = e.default_value;
  entries_[{index, sub}] = e;
}

const OdEntry* ObjectDictionary::find(uint16_t index, uint8_t sub) const
{
  const auto it = entries_.find({index, sub});
  return it == entries_.end() ? nullptr : &it->second;
}

bool ObjectDictionary::has_object(uint16_t index) const
{
  const auto it = entries_.lower_bound({index, 0});
  return it != entries_.end() && it->first.first == index;
}

uint32_t ObjectDictionary::sdo_read(uint16_t index, uint8_t sub, uint32_t* value, uint8_t* size) const
{
  const OdEntry* e = find(index, sub);
  if (!e) return has_object(index) ? sdo::kNoSubIndex : sdo::kNoObject;
  if (e->access == Access::kWo) return sdo::kWriteOnly;
  *value = e->value;
  *size = e->size;
  return 0;
}

uint32_t ObjectDictionary::sdo_write(uint16_t index, uint8_t sub, uint32_t value, uint8_t size)
{
  auto it = entries_.find({index, sub});
  if (it == entries_.end()) return has_object(index) ? sdo::kNoSubIndex : sdo::kNoObject;
  OdEntry& e = it->second;
  if (e.access == Access::kConst || e.access == Access::kRo) return sdo::kReadOnly;
  if (size != 0 && size != e.size) return size > e.size ? sdo::kLengthTooHigh : sdo::kLengthTooLow;
  value = truncate(value, e.size);
  if (check_) {
    if (const uint32_t abort = check_(index, sub, value); abort != 0) return abort;
  }
  e.value = value;
  if (hook_) hook_(index, sub);
  return 0;
}

void ObjectDictionary::pdo_write(uint16_t index, uint8_t sub, uint32_t value)
{
  auto it = entries_.find({index, sub});
  if (it == entries_.end()) return;
  it->second.value = truncate(value, it->second.size);
  if (hook_) hook_(index, sub);
}

uint32_t ObjectDictionary::get(uint16_t index, uint8_t sub) const
{
  const OdEntry* e = find(index, sub);
  return e ? e->value : 0;
}

int32_t ObjectDictionary::get_signed(uint16_t index, uint8_t sub) const
{
  const OdEntry* e = find(index, sub);
  if (!e) return 0;
  switch (e->size) {
    case 1: return static_cast<int8_t>(e->value);
    case 2: return static_cast<int16_t>(e->value);
    default: return static_cast<int32_t>(e->value);
  }
}

void ObjectDictionary::set(uint16_t index, uint8_t sub, uint32_t value)
{
  auto it = entries_.find({index, sub});
  if (it != entries_.end()) it->second.value = truncate(value, it->second.size);
}

void ObjectDictionary::reset(uint16_t lo, uint16_t hi)
{
  for (auto& [key, e] : entries_)
    if (key.first >= lo && key.first <= hi) e.value = e.default_value;
}

}  // namespace rgnav::can::emulator
