// Targeted hostile inputs for the generated wire validators. The exhaustive per-type fuzzing
// lives in tests/fuzz; these pin down the cases that crash or exhaust lcm-gen's decoders.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "bus/typed.h"

namespace rgnav {
namespace {

std::vector<uint8_t> encode_raw(const laser_scan_t& s)
{
  std::vector<uint8_t> buf(static_cast<size_t>(s.getEncodedSize()));
  EXPECT_GE(s.encode(buf.data(), 0, static_cast<int>(buf.size())), 0);
  return buf;
}

laser_scan_t scan()
{
  laser_scan_t s{};
  s.utime = 1;
  s.scan_id = 1;
  s.sensor = "l";
  s.angle_increment = 0.01f;
  s.range_max = 8;
  s.nranges = 3;
  s.ranges = {1, 2, 3};
  return s;
}

void put_be32(std::vector<uint8_t>* b, size_t at, int32_t v)
{
  const auto u = static_cast<uint32_t>(v);
  (*b)[at] = static_cast<uint8_t>(u >> 24);
  (*b)[at + 1] = static_cast<uint8_t>(u >> 16);
  (*b)[at + 2] = static_cast<uint8_t>(u >> 8);
  (*b)[at + 3] = static_cast<uint8_t>(u);
}

// Byte offsets in an encoded laser_scan_t: 8 fingerprint, 8 utime, 8 scan_id, then sensor.
constexpr size_t kSensorLen = 24;
constexpr size_t kNranges = kSensorLen + 4 + 2 + 5 * 4;

TEST(WireValidator, AcceptsValid)
{
  const auto b = encode_raw(scan());
  std::string why;
  EXPECT_TRUE(wire::validate<laser_scan_t>(b.data(), b.size(), &why)) << why;
}

TEST(WireValidator, HugeArrayCountRefusedWithoutAllocating)
{
  auto b = encode_raw(scan());
  put_be32(&b, kNranges, 0x7fffffff);
  std::string why;
  EXPECT_FALSE(wire::validate<laser_scan_t>(b.data(), b.size(), &why));
  EXPECT_NE(why.find("'ranges'"), std::string::npos) << why;
  laser_scan_t out;
  EXPECT_FALSE(bus::decode(b.data(), b.size(), &out, &why));
}

TEST(WireValidator, NegativeArrayCountRefused)
{
  auto b = encode_raw(scan());
  put_be32(&b, kNranges, -1);
  std::string why;
  EXPECT_FALSE(wire::validate<laser_scan_t>(b.data(), b.size(), &why));
}

TEST(WireValidator, ZeroAndNegativeStringLengthRefused)
{
  // lcm-gen's decoder would call std::string::assign(p, len - 1) with len 0: a huge length.
  for (int32_t len : {0, -5, 1 << 30}) {
    auto b = encode_raw(scan());
    put_be32(&b, kSensorLen, len);
    std::string why;
    EXPECT_FALSE(wire::validate<laser_scan_t>(b.data(), b.size(), &why)) << len;
  }
}

TEST(WireValidator, TruncatedAtEveryLengthRefused)
{
  const auto b = encode_raw(scan());
  for (size_t n = 0; n < b.size(); ++n) {
    std::string why;
    EXPECT_FALSE(wire::validate<laser_scan_t>(b.data(), n, &why)) << n;
  }
}

TEST(WireValidator, TrailingBytesRefused)
{
  auto b = encode_raw(scan());
  b.push_back(0);
  std::string why;
  EXPECT_FALSE(wire::validate<laser_scan_t>(b.data(), b.size(), &why));
}

TEST(WireValidator, UnknownEnumRefused)
{
  odometry_t o{};
  o.utime = 1;
  o.status = 42;
  std::vector<uint8_t> b(static_cast<size_t>(o.getEncodedSize()));
  o.encode(b.data(), 0, static_cast<int>(b.size()));
  std::string why;
  EXPECT_FALSE(wire::validate<odometry_t>(b.data(), b.size(), &why));
  EXPECT_NE(why.find("STATUS_"), std::string::npos) << why;
}

TEST(WireValidator, FixedSizeArrayOfStructsChecked)
{
  // Nested structs and fixed arrays: a NaN deep inside an rg_map_t is found.
  rg_map_t m{};
  m.utime = 1;
  m.nregions = 1;
  region_t r{};
  r.id = 1;
  r.name = "office";
  r.state = region_t::STATE_OPEN;
  r.nsegments = 1;
  r.segments.resize(1);
  r.segments[0].b.x = 1.0;
  m.regions.push_back(r);
  std::string why;
  ASSERT_TRUE(counts_consistent(m, &why)) << why;
  std::vector<uint8_t> b(static_cast<size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  EXPECT_TRUE(wire::validate<rg_map_t>(b.data(), b.size(), &why)) << why;
  m.regions[0].segments[0].b.x = NAN;
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  EXPECT_FALSE(wire::validate<rg_map_t>(b.data(), b.size(), &why));
}

TEST(CountsConsistent, NestedMismatchFound)
{
  rg_map_t m{};
  m.nregions = 1;
  m.regions.resize(1);
  m.regions[0].nsegments = 2;  // but no segments
  std::string why;
  EXPECT_FALSE(counts_consistent(m, &why));
  EXPECT_NE(why.find("region_t.segments"), std::string::npos) << why;
}

}  // namespace
}  // namespace rgnav
