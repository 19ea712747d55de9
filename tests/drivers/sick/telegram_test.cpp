// Framing and the command / reply encoders and decoders: round trips, and refusal of
// malformed input.
#include <gtest/gtest.h>

#include "commands.h"
#include "measured_values.h"
#include "telegram.h"

namespace rgnav::drivers::sick {
namespace {

TEST(Framing, RoundTripAndLength)
{
  const Telegram t = make_reply(reply::kStatus, std::vector<uint8_t>(152, 0x5A), 0x10);
  const auto bytes = frame(t);
  ASSERT_EQ(bytes.size(), framed_size(154));
  EXPECT_EQ(bytes[0], kStx);
  EXPECT_EQ(bytes[1], kAddressHost);
  EXPECT_EQ(get_u16(&bytes[2]), 154);
  const auto back = unframe(bytes.data(), bytes.size());
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, t);
  const auto r = as_reply(*back);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->command, reply::kStatus);
  EXPECT_EQ(r->data.size(), 152u);
  EXPECT_EQ(r->status, 0x10);
}

TEST(Framing, RejectsBadCrcLengthAndStx)
{
  auto bytes = frame(request_status());
  auto bad = bytes;
  bad.back() ^= 1;
  EXPECT_FALSE(unframe(bad.data(), bad.size()));
  bad = bytes;
  bad[0] = 0x03;
  EXPECT_FALSE(unframe(bad.data(), bad.size()));
  EXPECT_FALSE(unframe(bytes.data(), bytes.size() - 1));
  EXPECT_THROW(frame(kAddressLms, {}), std::length_error);
  EXPECT_THROW(frame(kAddressLms, std::vector<uint8_t>(kMaxPayload + 1, 0)), std::length_error);
}

TEST(Commands, ModeReplyRoundTrip)
{
  const auto r = as_reply(encode_mode_reply(0x01, 0x00));
  ASSERT_TRUE(r);
  EXPECT_EQ(decode_mode_reply(*r), 0x01);
  Reply wrong = *r;
  wrong.command = reply::kVariant;
  EXPECT_FALSE(decode_mode_reply(wrong));
}

TEST(Commands, VariantRoundTripAndSupport)
{
  VariantReply v{true, {100, 25}};
  const auto back = decode_variant_reply(*as_reply(encode_variant_reply(v, 0)));
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->accepted);
  EXPECT_EQ(back->variant, (Variant{100, 25}));
  EXPECT_TRUE(variant_supported({180, 100}));
  EXPECT_TRUE(variant_supported({180, 50}));
  EXPECT_FALSE(variant_supported({180, 25}));
  EXPECT_FALSE(variant_supported({90, 100}));
  EXPECT_EQ(variant_beam_count({180, 100}), 181);
  EXPECT_EQ(variant_beam_count({180, 50}), 361);
  EXPECT_EQ(variant_beam_count({100, 25}), 401);
  EXPECT_EQ(variant_rotations({180, 50}), 2);
  const auto req = request_variant({180, 50});
  EXPECT_EQ(req.payload, (std::vector<uint8_t>{0x3B, 0xB4, 0x00, 0x32, 0x00}));
}

TEST(Commands, ConfigReadModifyWriteKeepsOtherBytes)
{
  ConfigBlock c;
  for (size_t i = 0; i < c.bytes.size(); ++i) c.bytes[i] = static_cast<uint8_t>(i * 7);
  auto read = decode_config_reply(*as_reply(encode_config_reply(c, 0)));
  ASSERT_TRUE(read);
  EXPECT_EQ(*read, c);
  read->set_units(Units::kMillimetres);
  read->set_measuring_mode(kMeasuringMode8m80mFieldsDazzle);
  const auto req = request_set_config(*read);
  ASSERT_EQ(req.payload.size(), 1 + ConfigBlock::kSize);
  EXPECT_EQ(req.payload[0], cmd::kSetConfig);
  for (size_t i = 0; i < ConfigBlock::kSize; ++i) {
    if (i == ConfigBlock::kUnitsIndex) EXPECT_EQ(req.payload[1 + i], 0x01);
    else if (i == ConfigBlock::kMeasuringModeIndex) EXPECT_EQ(req.payload[1 + i], 0x00);
    else EXPECT_EQ(req.payload[1 + i], c.bytes[i]) << i;
  }
  const auto written = decode_set_config_reply(*as_reply(encode_set_config_reply({true, *read}, 0)));
  ASSERT_TRUE(written);
  EXPECT_TRUE(written->accepted);
  EXPECT_EQ(written->config, *read);
  Reply short_reply{reply::kConfig, std::vector<uint8_t>(10, 0), 0};
  EXPECT_FALSE(decode_config_reply(short_reply));
}

TEST(Commands, StatusRoundTrip)
{
  StatusReport s;
  s.software_version = "V02.10";
  s.operating_mode = 0x24;
  s.device_status = 0;
  s.manufacturer = "SICK AG";
  s.measuring_mode = 0;
  s.variant = {180, 50};
  s.units = Units::kMillimetres;
  const Telegram t = encode_status_reply(s, 0);
  EXPECT_EQ(t.payload.size(), 1 + StatusReport::kSize + 1);
  const auto back = decode_status_reply(*as_reply(t));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->software_version, "V02.10");
  EXPECT_EQ(back->manufacturer, "SICK AG");
  EXPECT_EQ(back->operating_mode, 0x24);
  EXPECT_EQ(back->variant, (Variant{180, 50}));
  EXPECT_EQ(back->units, Units::kMillimetres);
}

TEST(Commands, InstallationPasswordIsEightCharacters)
{
  EXPECT_EQ(request_installation_mode("abc").payload.size(), 10u);
  EXPECT_EQ(request_installation_mode("abc").payload[9], ' ');
}

TEST(MeasuredValues, RoundTripWithUnitsFlagsAndPartialIndex)
{
  MeasuredValues m;
  m.units = Units::kMillimetres;
  m.partial_scan_index = 2;
  m.values = {0, 1, 4095, 8182, kNoReturnCode, 8191};
  m.flags = {0, 1, 2, 4, 7, 0};
  m.status = 0x10;
  const Telegram t = encode_measured_values(m);
  EXPECT_EQ(t.command(), reply::kMeasuredValues);
  // COUNT word: 6 values, partial index 2 in bits 11-12, mm in bits 14-15.
  EXPECT_EQ(get_u16(&t.payload[1]), 6 | (2 << 11) | (1 << 14));
  // Value 2 (4095, flags 2 = field B): bit 14 set above the 13-bit distance.
  EXPECT_EQ(get_u16(&t.payload[1 + 2 + 2 * 2]), 4095 | (2 << 13));
  const auto back = decode_measured_values(*as_reply(t));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->units, Units::kMillimetres);
  EXPECT_EQ(back->partial_scan_index, 2);
  EXPECT_FALSE(back->partial_scan);
  EXPECT_EQ(back->values, m.values);
  EXPECT_EQ(back->flags, m.flags);
  EXPECT_EQ(back->status, 0x10);
}

TEST(MeasuredValues, CountMustMatchLength)
{
  MeasuredValues m;
  m.values.assign(181, 1000);
  auto r = *as_reply(encode_measured_values(m));
  r.data.pop_back();
  EXPECT_FALSE(decode_measured_values(r));
  r.data.pop_back();  // now one value short of what COUNT says
  EXPECT_FALSE(decode_measured_values(r));
}

TEST(MeasuredValues, Classification)
{
  EXPECT_EQ(classify_value(0), ValueKind::kRange);
  EXPECT_EQ(classify_value(8182), ValueKind::kRange);
  EXPECT_EQ(classify_value(8183), ValueKind::kNoReturn);
  EXPECT_EQ(classify_value(8190), ValueKind::kInvalid);  // dazzle
  EXPECT_EQ(classify_value(8191), ValueKind::kInvalid);
}

}  // namespace
}  // namespace rgnav::drivers::sick
