#include "emulator/drive_object_dictionary.h"

namespace rgnav::can::emulator {

namespace {

constexpr bool kSigned = true, kUnsigned = false, kMap = true, kNoMap = false;

// One PDO's EDS defaults: COB-ID, transmission type, and its mapping (count, then the objects).
struct PdoDefaults
{
  uint32_t cob_id;
  uint8_t transmission_type;
  uint8_t mapped_count;
  uint32_t mapped[3];
};

// The communication record at `comm_index` and the mapping record at `map_index` of one PDO, in
// the order the EDS lists them. Transmit PDOs carry three more communication entries.
void add_pdo(ObjectDictionary& od, uint16_t comm_index, uint16_t map_index, const PdoDefaults& pdo, bool transmit)
{
  od.add(comm_index, 0, 1, kUnsigned, Access::kRo, kNoMap, transmit ? 5 : 2);  // highest sub-index
  od.add(comm_index, 1, 4, kUnsigned, Access::kRw, kNoMap, pdo.cob_id);
  od.add(comm_index, 2, 1, kUnsigned, Access::kRw, kNoMap, pdo.transmission_type);
  if (transmit) {
    od.add(comm_index, 3, 2, kUnsigned, Access::kRw, kNoMap, 0);  // inhibit time [100 us]
    od.add(comm_index, 4, 1, kUnsigned, Access::kRo, kNoMap, 0);  // compatibility entry
    od.add(comm_index, 5, 2, kUnsigned, Access::kRw, kNoMap, 0);  // event timer [ms]
  }
  od.add(map_index, 0, 1, kUnsigned, Access::kRw, kNoMap, pdo.mapped_count);
  for (uint8_t s = 0; s < 3; ++s) od.add(map_index, s + 1, 4, kUnsigned, Access::kRw, kNoMap, pdo.mapped[s]);
}

}  // namespace

ObjectDictionary make_drive_object_dictionary(uint8_t node_id, const DriveIdentity& id, const DriveDefaults& d)
{
  ObjectDictionary od;
  const uint32_t n = node_id;
  // --- CiA 301 communication profile ---
  od.add(0x1000, 0, 4, kUnsigned, Access::kConst, kNoMap, 0xFFFF0192);  // device type: CiA 402
  od.add(0x1001, 0, 1, kUnsigned, Access::kRo, kNoMap, 0);               // error register
  od.add(0x1005, 0, 4, kUnsigned, Access::kRw, kNoMap, 0x80);            // COB-ID SYNC
  od.add(0x100C, 0, 2, kUnsigned, Access::kRw, kNoMap, 0);               // guard time
  od.add(0x100D, 0, 1, kUnsigned, Access::kRw, kNoMap, 0);               // life time factor
  od.add(0x1014, 0, 4, kUnsigned, Access::kRw, kNoMap, n + 0x80);        // COB-ID EMCY
  od.add(0x1015, 0, 2, kUnsigned, Access::kRw, kNoMap, 0);               // inhibit time EMCY
  od.add(0x1016, 0, 1, kUnsigned, Access::kRo, kNoMap, 1);               // consumer heartbeat
  od.add(0x1016, 1, 4, kUnsigned, Access::kRw, kNoMap, 0);               //   node << 16 | ms
  od.add(0x1017, 0, 2, kUnsigned, Access::kRw, kNoMap, 0);               // producer heartbeat ms
  od.add(0x1018, 0, 1, kUnsigned, Access::kRo, kNoMap, 4);               // identity
  od.add(0x1018, 1, 4, kUnsigned, Access::kRo, kNoMap, id.vendor_id);
  od.add(0x1018, 2, 4, kUnsigned, Access::kRo, kNoMap, id.product_code);
  od.add(0x1018, 3, 4, kUnsigned, Access::kRo, kNoMap, id.revision);
  od.add(0x1018, 4, 4, kUnsigned, Access::kRo, kNoMap, id.serial);
  od.add(0x1029, 0, 1, kUnsigned, Access::kRo, kNoMap, 2);               // error behaviour
  od.add(0x1029, 1, 1, kUnsigned, Access::kRw, kNoMap, 0);               //   comm error: 0 = pre-op
  od.add(0x1029, 2, 1, kUnsigned, Access::kRw, kNoMap, 1);
  // RPDO communication (0x1400-0x1403) and mapping (0x1600-0x1603), defaults from the EDS.
  const PdoDefaults rpdo[4] = {{0x40000200 + n, 0xFF, 1, {0x60400010, 0, 0}},
                               {0x40000300 + n, 0xFF, 2, {0x60400010, 0x60600008, 0}},
                               {0x40000400 + n, 0xFF, 2, {0x60400010, 0x607A0020, 0}},
                               {0xC0000500 + n, 0xFE, 2, {0x60400010, 0x60FF0020, 0}}};
  for (uint16_t i = 0; i < 4; ++i) add_pdo(od, 0x1400 + i, 0x1600 + i, rpdo[i], false);
  // TPDO communication (0x1800-0x1803) and mapping (0x1A00-0x1A03).
  const PdoDefaults tpdo[4] = {{0x40000180 + n, 0x01, 1, {0x60410010, 0, 0}},
                               {0x40000280 + n, 0x01, 2, {0x60410010, 0x60610008, 0}},
                               {0x40000380 + n, 0x01, 2, {0x60410010, 0x60640020, 0}},
                               {0xC0000480 + n, 0xFE, 2, {0x60410010, 0x606C0020, 0}}};
  for (uint16_t i = 0; i < 4; ++i) add_pdo(od, 0x1800 + i, 0x1A00 + i, tpdo[i], true);
  // --- CiA 402 drive profile ---
  od.add(0x6007, 0, 2, kSigned, Access::kRw, kNoMap, 3);      // abort connection: 3 = quick stop
  od.add(0x6040, 0, 2, kUnsigned, Access::kRw, kMap, 0);      // controlword
  od.add(0x6041, 0, 2, kUnsigned, Access::kRo, kMap, 0);      // statusword
  od.add(0x605A, 0, 2, kSigned, Access::kRw, kNoMap, 2);      // quick stop option: ramp, then SOD
  od.add(0x605B, 0, 2, kSigned, Access::kRo, kNoMap, 0);      // shutdown option
  od.add(0x605C, 0, 2, kSigned, Access::kRo, kNoMap, 1);      // disable operation option
  od.add(0x605D, 0, 2, kSigned, Access::kRw, kNoMap, 1);      // halt option
  od.add(0x605E, 0, 2, kSigned, Access::kRo, kNoMap, 2);      // fault reaction: quick stop ramp
  od.add(0x6060, 0, 1, kSigned, Access::kRw, kMap, 0);        // modes of operation
  od.add(0x6061, 0, 1, kSigned, Access::kRo, kMap, 0);        // modes of operation display
  od.add(0x6062, 0, 4, kSigned, Access::kRo, kMap, 0);        // position demand
  od.add(0x6063, 0, 4, kSigned, Access::kRo, kMap, 0);        // position actual internal
  od.add(0x6064, 0, 4, kSigned, Access::kRo, kMap, 0);        // position actual [counts]
  od.add(0x6065, 0, 4, kUnsigned, Access::kRw, kNoMap, 0);    // following error window
  od.add(0x606B, 0, 4, kSigned, Access::kRo, kMap, 0);        // velocity demand [counts/s]
  od.add(0x606C, 0, 4, kSigned, Access::kRo, kMap, 0);        // velocity actual [counts/s]
  od.add(0x607A, 0, 4, kSigned, Access::kRw, kMap, 0);        // target position (pp, unused)
  od.add(0x607F, 0, 4, kUnsigned, Access::kRw, kNoMap, d.max_profile_velocity);
  od.add(0x6083, 0, 4, kUnsigned, Access::kRw, kNoMap, d.profile_acceleration);
  od.add(0x6084, 0, 4, kUnsigned, Access::kRw, kNoMap, d.profile_deceleration);
  od.add(0x6085, 0, 4, kUnsigned, Access::kRw, kNoMap, d.quick_stop_deceleration);
  od.add(0x60FF, 0, 4, kSigned, Access::kRw, kMap, 0);        // target velocity [counts/s]
  od.add(0x6502, 0, 4, kUnsigned, Access::kRo, kNoMap, 0xA5); // supported modes: pp, pv, hm, csp
  od.add(0x67FF, 0, 4, kUnsigned, Access::kRo, kNoMap, 0x00040192);
  return od;
}

}  // namespace rgnav::can::emulator
