// The object dictionary of the emulated CiA 402 drive: the communication objects of CiA 301
// (0x1000-0x1FFF) and the profile-velocity subset of CiA 402 (0x6000-), with data types,
// access rights, PDO mappability and defaults taken from the EDS of a CiA 402 drive
// (shared/data/canopen/cia402_slave.eds; $NODEID defaults resolved for `node_id`). Objects the
// EDS lacks but profile velocity needs (0x6007, 0x606B, 0x607F) follow CiA 402.
#pragma once

#include <cstdint>

#include "emulator/object_dictionary.h"

namespace rgnav::can::emulator {

struct DriveIdentity
{
  uint32_t vendor_id = 0x555;     // 0x1018:1 (EDS)
  uint32_t product_code = 0x1;    // 0x1018:2
  uint32_t revision = 0x0;        // 0x1018:3
  uint32_t serial = 0x0;          // 0x1018:4
};

struct DriveDefaults
{
  uint32_t profile_acceleration = 10000;     // 0x6083 [counts/s^2]
  uint32_t profile_deceleration = 10000;     // 0x6084 [counts/s^2]
  uint32_t quick_stop_deceleration = 50000;  // 0x6085 [counts/s^2]
  uint32_t max_profile_velocity = 1000000;   // 0x607F [counts/s]
};

ObjectDictionary make_drive_object_dictionary(uint8_t node_id, const DriveIdentity& identity,
                                              const DriveDefaults& defaults);

}  // namespace rgnav::can::emulator
