// Requests the driver sends and the replies it reads, as plain values. Encoders return a
// Telegram addressed to the LMS; decoders take a Reply (see telegram.h) and return nullopt
// when it is not the expected reply or is too short — never read past the data.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "telegram.h"

namespace rgnav::drivers::sick {

// Operating modes of command 0x20 that this driver uses.
enum class OperatingMode : uint8_t
{
  kInstallation = 0x00,      // needs the password; allows writing the configuration (0x77)
  kContinuousAll = 0x24,     // continuous output of all measured values (0xB0 telegrams)
  kValuesOnRequest = 0x25,   // monitoring, values on request only: "stop streaming"
};

// Serial rates of the LMS 2xx and their mode codes for command 0x20.
enum class Baud : uint8_t
{
  k38400 = 0x40,
  k19200 = 0x41,
  k9600 = 0x42,
  k500000 = 0x48,
};
int baud_bits_per_second(Baud b);
std::optional<Baud> baud_from_bits_per_second(int bps);

constexpr const char* kDefaultInstallationPassword = "SICK_LMS";

// Measured value units (configuration byte E / bits 14-15 of the 0xB0 count word).
enum class Units : uint8_t
{
  kCentimetres = 0x00,  // "80 m mode": 13-bit values in cm
  kMillimetres = 0x01,  // "8 m mode": 13-bit values in mm
  kDecimetres = 0x02,   // only in some special variants; decoded, never requested
};
double units_in_metres(Units u);

// Measuring modes (configuration byte D). Mode 0 is the default: 13-bit values in the
// 8 m / 80 m range with field A, field B and dazzle flags in bits 13..15.
constexpr uint8_t kMeasuringMode8m80mFieldsDazzle = 0x00;

// Scan angle (degrees) and angular resolution (1/100 degree) of the 0x3B variant command.
struct Variant
{
  uint16_t angle_deg = 180;       // 100 or 180
  uint16_t resolution_cdeg = 100; // 25, 50 or 100
  bool operator==(const Variant& o) const { return angle_deg == o.angle_deg && resolution_cdeg == o.resolution_cdeg; }
};
// The LMS 2xx accepts 180°/1°, 180°/0.5°, 100°/1°, 100°/0.5°, 100°/0.25°.
bool variant_supported(const Variant& v);
// Beams per scan (181, 361, 101, 201, 401) and mirror rotations it takes (1, 2, 4): finer
// resolutions interlace several rotations shifted by a fraction of a degree.
int variant_beam_count(const Variant& v);
int variant_rotations(const Variant& v);

// The configuration block of 0x74 / 0x77 (34 bytes on an LMS 291: blocks A..A4 of the
// telegram listing). Kept as raw bytes so a read-modify-write changes only what we mean.
struct ConfigBlock
{
  static constexpr size_t kSize = 34;
  static constexpr size_t kMeasuringModeIndex = 5;  // block D
  static constexpr size_t kUnitsIndex = 6;          // block E
  std::vector<uint8_t> bytes = std::vector<uint8_t>(kSize, 0);

  uint8_t measuring_mode() const { return bytes[kMeasuringModeIndex]; }
  Units units() const { return static_cast<Units>(bytes[kUnitsIndex]); }
  void set_measuring_mode(uint8_t m) { bytes[kMeasuringModeIndex] = m; }
  void set_units(Units u) { bytes[kUnitsIndex] = static_cast<uint8_t>(u); }
  bool operator==(const ConfigBlock& o) const { return bytes == o.bytes; }
};

// What the driver reads from the 0xB1 status reply (152 data bytes; offsets are data
// offsets, i.e. one less than the payload offsets of the telegram listing).
struct StatusReport
{
  static constexpr size_t kSize = 152;
  std::string software_version;  // block A, 7 characters
  uint8_t operating_mode = 0;    // block B
  uint8_t device_status = 0;     // block C: 0 ok, 1 error
  std::string manufacturer;      // block D, 8 characters
  uint8_t measuring_mode = 0;
  Variant variant;
  Units units = Units::kCentimetres;
};

// ---- requests (host → LMS) ----
Telegram request_reset();
Telegram request_mode(OperatingMode mode);
Telegram request_installation_mode(const std::string& password = kDefaultInstallationPassword);
Telegram request_baud(Baud baud);
Telegram request_status();
Telegram request_variant(const Variant& v);
Telegram request_config();
Telegram request_set_config(const ConfigBlock& c);

// ---- replies (LMS → host) ----
// 0xA0: 0x00 = mode switched; 0x01 = refused (bad password); 0x02 = refused (device fault).
std::optional<uint8_t> decode_mode_reply(const Reply& r);
struct VariantReply
{
  bool accepted = false;
  Variant variant;
};
std::optional<VariantReply> decode_variant_reply(const Reply& r);
std::optional<ConfigBlock> decode_config_reply(const Reply& r);  // 0xF4
struct SetConfigReply
{
  bool accepted = false;
  ConfigBlock config;
};
std::optional<SetConfigReply> decode_set_config_reply(const Reply& r);  // 0xF7
std::optional<StatusReport> decode_status_reply(const Reply& r);        // 0xB1

// Encoders of the device side (the emulator), kept next to their decoders so the two stay
// in step and round-trip tests cover both.
Telegram encode_mode_reply(uint8_t result, uint8_t status);
Telegram encode_variant_reply(const VariantReply& v, uint8_t status);
Telegram encode_config_reply(const ConfigBlock& c, uint8_t status);
Telegram encode_set_config_reply(const SetConfigReply& c, uint8_t status);
Telegram encode_status_reply(const StatusReport& s, uint8_t status);

}  // namespace rgnav::drivers::sick
