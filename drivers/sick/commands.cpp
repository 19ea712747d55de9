#include "commands.h"

#include <algorithm>

namespace rgnav::drivers::sick {

namespace {

Telegram request(std::vector<uint8_t> payload)
{
  Telegram t;
  t.address = kAddressLms;
  t.payload = std::move(payload);
  return t;
}

// Status report data offsets (payload offset - 1).
constexpr size_t kStVersion = 0;         // 7 bytes
constexpr size_t kStOperatingMode = 7;
constexpr size_t kStDeviceStatus = 8;
constexpr size_t kStManufacturer = 9;    // 8 bytes
constexpr size_t kStMeasuringMode = 101;
constexpr size_t kStScanAngle = 106;     // u16
constexpr size_t kStResolution = 108;    // u16
constexpr size_t kStUnits = 121;

std::string fixed_string(const std::vector<uint8_t>& d, size_t at, size_t n)
{
  std::string s(d.begin() + static_cast<long>(at), d.begin() + static_cast<long>(at + n));
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return s;
}

void put_fixed_string(std::vector<uint8_t>* d, size_t at, size_t n, const std::string& s)
{
  for (size_t i = 0; i < n; ++i) (*d)[at + i] = i < s.size() ? static_cast<uint8_t>(s[i]) : ' ';
}

}  // namespace

int baud_bits_per_second(Baud b)
{
  switch (b) {
    case Baud::k9600: return 9600;
    case Baud::k19200: return 19200;
    case Baud::k38400: return 38400;
    case Baud::k500000: return 500000;
  }
  return 0;
}

std::optional<Baud> baud_from_bits_per_second(int bps)
{
  switch (bps) {
    case 9600: return Baud::k9600;
    case 19200: return Baud::k19200;
    case 38400: return Baud::k38400;
    case 500000: return Baud::k500000;
    default: return std::nullopt;
  }
}

double units_in_metres(Units u)
{
  switch (u) {
    case Units::kMillimetres: return 0.001;
    case Units::kCentimetres: return 0.01;
    case Units::kDecimetres: return 0.1;
  }
  return 0.0;
}

bool variant_supported(const Variant& v)
{
  if (v.angle_deg == 180) return v.resolution_cdeg == 100 || v.resolution_cdeg == 50;
  if (v.angle_deg == 100) return v.resolution_cdeg == 100 || v.resolution_cdeg == 50 || v.resolution_cdeg == 25;
  return false;
}

int variant_beam_count(const Variant& v) { return v.angle_deg * 100 / v.resolution_cdeg + 1; }
int variant_rotations(const Variant& v) { return 100 / v.resolution_cdeg; }

Telegram request_reset() { return request({cmd::kReset}); }

Telegram request_mode(OperatingMode mode) { return request({cmd::kSwitchMode, static_cast<uint8_t>(mode)}); }

Telegram request_installation_mode(const std::string& password)
{
  // The password is always 8 characters; shorter ones are padded with blanks.
  std::vector<uint8_t> p{cmd::kSwitchMode, static_cast<uint8_t>(OperatingMode::kInstallation)};
  for (size_t i = 0; i < 8; ++i) p.push_back(i < password.size() ? static_cast<uint8_t>(password[i]) : ' ');
  return request(std::move(p));
}

Telegram request_baud(Baud baud) { return request({cmd::kSwitchMode, static_cast<uint8_t>(baud)}); }

Telegram request_status() { return request({cmd::kRequestStatus}); }

Telegram request_variant(const Variant& v)
{
  std::vector<uint8_t> p{cmd::kSetVariant};
  put_u16(&p, v.angle_deg);
  put_u16(&p, v.resolution_cdeg);
  return request(std::move(p));
}

Telegram request_config() { return request({cmd::kRequestConfig}); }

Telegram request_set_config(const ConfigBlock& c)
{
  std::vector<uint8_t> p{cmd::kSetConfig};
  p.insert(p.end(), c.bytes.begin(), c.bytes.end());
  return request(std::move(p));
}

std::optional<uint8_t> decode_mode_reply(const Reply& r)
{
  if (r.command != reply::kSwitchMode || r.data.size() != 1) return std::nullopt;
  return r.data[0];
}

std::optional<VariantReply> decode_variant_reply(const Reply& r)
{
  if (r.command != reply::kVariant || r.data.size() != 5) return std::nullopt;
  VariantReply v;
  v.accepted = r.data[0] == 0x01;
  v.variant.angle_deg = get_u16(&r.data[1]);
  v.variant.resolution_cdeg = get_u16(&r.data[3]);
  return v;
}

std::optional<ConfigBlock> decode_config_reply(const Reply& r)
{
  if (r.command != reply::kConfig || r.data.size() != ConfigBlock::kSize) return std::nullopt;
  ConfigBlock c;
  c.bytes = r.data;
  return c;
}

std::optional<SetConfigReply> decode_set_config_reply(const Reply& r)
{
  if (r.command != reply::kSetConfig || r.data.size() != ConfigBlock::kSize + 1) return std::nullopt;
  SetConfigReply s;
  s.accepted = r.data[0] == 0x01;
  s.config.bytes.assign(r.data.begin() + 1, r.data.end());
  return s;
}

std::optional<StatusReport> decode_status_reply(const Reply& r)
{
  if (r.command != reply::kStatus || r.data.size() != StatusReport::kSize) return std::nullopt;
  StatusReport s;
  s.software_version = fixed_string(r.data, kStVersion, 7);
  s.operating_mode = r.data[kStOperatingMode];
  s.device_status = r.data[kStDeviceStatus];
  s.manufacturer = fixed_string(r.data, kStManufacturer, 8);
  s.measuring_mode = r.data[kStMeasuringMode];
  s.variant.angle_deg = get_u16(&r.data[kStScanAngle]);
  s.variant.resolution_cdeg = get_u16(&r.data[kStResolution]);
  s.units = static_cast<Units>(r.data[kStUnits]);
  return s;
}

Telegram encode_mode_reply(uint8_t result, uint8_t status) { return make_reply(reply::kSwitchMode, {result}, status); }

Telegram encode_variant_reply(const VariantReply& v, uint8_t status)
{
  std::vector<uint8_t> d{static_cast<uint8_t>(v.accepted ? 0x01 : 0x00)};
  put_u16(&d, v.variant.angle_deg);
  put_u16(&d, v.variant.resolution_cdeg);
  return make_reply(reply::kVariant, d, status);
}

Telegram encode_config_reply(const ConfigBlock& c, uint8_t status) { return make_reply(reply::kConfig, c.bytes, status); }

Telegram encode_set_config_reply(const SetConfigReply& c, uint8_t status)
{
  std::vector<uint8_t> d{static_cast<uint8_t>(c.accepted ? 0x01 : 0x00)};
  d.insert(d.end(), c.config.bytes.begin(), c.config.bytes.end());
  return make_reply(reply::kSetConfig, d, status);
}

Telegram encode_status_reply(const StatusReport& s, uint8_t status)
{
  std::vector<uint8_t> d(StatusReport::kSize, 0);
  put_fixed_string(&d, kStVersion, 7, s.software_version);
  d[kStOperatingMode] = s.operating_mode;
  d[kStDeviceStatus] = s.device_status;
  put_fixed_string(&d, kStManufacturer, 8, s.manufacturer);
  d[kStMeasuringMode] = s.measuring_mode;
  d[kStScanAngle] = static_cast<uint8_t>(s.variant.angle_deg & 0xFF);
  d[kStScanAngle + 1] = static_cast<uint8_t>(s.variant.angle_deg >> 8);
  d[kStResolution] = static_cast<uint8_t>(s.variant.resolution_cdeg & 0xFF);
  d[kStResolution + 1] = static_cast<uint8_t>(s.variant.resolution_cdeg >> 8);
  d[kStUnits] = static_cast<uint8_t>(s.units);
  return make_reply(reply::kStatus, d, status);
}

}  // namespace rgnav::drivers::sick
