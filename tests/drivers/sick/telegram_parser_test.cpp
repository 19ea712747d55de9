// The streaming parser against what a real serial line delivers: telegrams split anywhere,
// garbage, ACK/NAK bytes, broken CRCs, impossible lengths, false starts.
#include <gtest/gtest.h>

#include <random>

#include "commands.h"
#include "measured_values.h"
#include "telegram_parser.h"

namespace rgnav::drivers::sick {
namespace {

std::vector<uint8_t> scan_bytes(uint16_t fill, size_t n = 181)
{
  MeasuredValues m;
  m.values.assign(n, fill);
  return frame(encode_measured_values(m));
}

std::vector<uint8_t> cat(std::initializer_list<std::vector<uint8_t>> parts)
{
  std::vector<uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

std::vector<Telegram> feed_all(TelegramParser& p, const std::vector<uint8_t>& bytes)
{
  std::vector<Telegram> out;
  for (auto& rt : p.feed(bytes.data(), bytes.size()).telegrams) out.push_back(rt.telegram);
  return out;
}

TEST(TelegramParser, WholeTelegramsInOneChunk)
{
  TelegramParser p(kAddressHost);
  const auto got = feed_all(p, cat({scan_bytes(100), frame(encode_mode_reply(0, 0)), scan_bytes(200)}));
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[1].command(), reply::kSwitchMode);
  EXPECT_EQ(decode_measured_values(*as_reply(got[2]))->values[0], 200);
  EXPECT_EQ(p.stats().resyncs, 0u);
  EXPECT_EQ(p.buffered(), 0u);
}

TEST(TelegramParser, EverySplitPointAndRandomChunks)
{
  const auto stream = cat({scan_bytes(1), frame(encode_mode_reply(0, 0)), scan_bytes(2)});
  for (size_t cut = 0; cut <= stream.size(); ++cut) {
    TelegramParser p(kAddressHost);
    auto a = p.feed(stream.data(), cut).telegrams.size();
    a += p.feed(stream.data() + cut, stream.size() - cut).telegrams.size();
    ASSERT_EQ(a, 3u) << "cut at " << cut;
  }
  std::mt19937 rng(42);
  TelegramParser p(kAddressHost);
  size_t got = 0, pos = 0;
  while (pos < stream.size()) {
    const size_t n = std::min<size_t>(stream.size() - pos, 1 + rng() % 17);
    got += p.feed(stream.data() + pos, n).telegrams.size();
    pos += n;
  }
  EXPECT_EQ(got, 3u);
}

TEST(TelegramParser, ResynchronisesAfterGarbage)
{
  TelegramParser p(kAddressHost);
  // Garbage includes an STX with the right address but a length that is impossible.
  const std::vector<uint8_t> garbage{0xFF, 0x13, kStx, kAddressHost, 0xFF, 0xFF, 0x77, kStx, 0x42};
  const auto got = feed_all(p, cat({garbage, scan_bytes(300), garbage, scan_bytes(301)}));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(decode_measured_values(*as_reply(got[1]))->values[0], 301);
  EXPECT_EQ(p.stats().resyncs, 2u);
  EXPECT_GE(p.stats().bad_headers, 4u);
  EXPECT_EQ(p.stats().crc_errors, 0u);
}

TEST(TelegramParser, BadCrcDropsThatTelegramOnly)
{
  TelegramParser p(kAddressHost);
  auto broken = scan_bytes(500);
  broken.back() ^= 0xFF;
  const auto got = feed_all(p, cat({scan_bytes(499), broken, scan_bytes(501)}));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(decode_measured_values(*as_reply(got[0]))->values[0], 499);
  EXPECT_EQ(decode_measured_values(*as_reply(got[1]))->values[0], 501);
  EXPECT_EQ(p.stats().crc_errors, 1u);
}

TEST(TelegramParser, TruncatedTelegramDoesNotSwallowTheNext)
{
  // A telegram cut short (line dropped mid-frame): its header promises more bytes, so the
  // next telegram is consumed into the candidate, the CRC fails, and the parser finds the
  // next telegram again by restarting one byte after the false start.
  TelegramParser p(kAddressHost);
  auto cut = scan_bytes(7);
  cut.resize(cut.size() / 2);
  const auto got = feed_all(p, cat({cut, scan_bytes(8), scan_bytes(9), scan_bytes(10)}));
  ASSERT_GE(got.size(), 2u);
  EXPECT_EQ(decode_measured_values(*as_reply(got.back()))->values[0], 10);
  EXPECT_GE(p.stats().crc_errors, 1u);
}

TEST(TelegramParser, OversizeLengthRejectedWithoutWaiting)
{
  TelegramParser p(kAddressHost, 100);
  // Length 101 > bound 100: rejected immediately, the good telegram right after is found.
  const std::vector<uint8_t> big{kStx, kAddressHost, 101, 0};
  const auto got = feed_all(p, cat({big, frame(encode_mode_reply(0, 0))}));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(p.stats().bad_headers, 1u);
  // A scan longer than the bound is refused too (its CRC is never trusted).
  EXPECT_TRUE(feed_all(p, scan_bytes(1)).empty());
  EXPECT_LE(p.buffered(), 4u + 100u + 2u);
}

TEST(TelegramParser, ReportsAckAndNakAndIgnoresOtherAddresses)
{
  TelegramParser p(kAddressHost);
  const auto request = frame(request_mode(OperatingMode::kContinuousAll));  // address 0x00: not for the host
  const auto out = p.feed(cat({{kAck}, request, {kNak}, frame(encode_mode_reply(0, 0))}).data(),
                          cat({{kAck}, request, {kNak}, frame(encode_mode_reply(0, 0))}).size());
  EXPECT_EQ(out.acks, 1);
  EXPECT_EQ(out.naks, 1);
  ASSERT_EQ(out.telegrams.size(), 1u);
  EXPECT_EQ(out.telegrams[0].telegram.command(), reply::kSwitchMode);
}

TEST(TelegramParser, ReceiveTimeIsThatOfTheChunkWithTheLastByte)
{
  TelegramParser p(kAddressHost);
  const auto b = scan_bytes(1);
  EXPECT_TRUE(p.feed(b.data(), 100, 1000).telegrams.empty());
  EXPECT_TRUE(p.feed(b.data() + 100, b.size() - 101, 2000).telegrams.empty());
  const auto out = p.feed(b.data() + b.size() - 1, 1, 3000);
  ASSERT_EQ(out.telegrams.size(), 1u);
  EXPECT_EQ(out.telegrams[0].rx_utime, 3000);
}

TEST(TelegramParser, TelegramsReadTogetherKnowWhatCameAfterThem)
{
  TelegramParser p(kAddressHost);
  const auto a = scan_bytes(1);
  const auto b = frame(encode_mode_reply(0, 0));
  const auto both = cat({a, b, {0x33}});
  const auto out = p.feed(both.data(), both.size(), 5000);
  ASSERT_EQ(out.telegrams.size(), 2u);
  EXPECT_EQ(out.telegrams[0].rx_utime, 5000);
  EXPECT_EQ(out.telegrams[0].trailing_bytes, b.size() + 1);
  EXPECT_EQ(out.telegrams[1].trailing_bytes, 1u);
}

TEST(TelegramParser, RandomNoiseNeverCrashesAndRecovers)
{
  std::mt19937 rng(7);
  TelegramParser p(kAddressHost);
  std::vector<uint8_t> noise(20000);
  for (auto& b : noise) b = static_cast<uint8_t>(rng());
  p.feed(noise.data(), noise.size());
  // Whatever the noise left half-parsed, good telegrams get through after at most one
  // bounded false candidate.
  size_t got = 0;
  for (int i = 0; i < 4; ++i) got += feed_all(p, scan_bytes(static_cast<uint16_t>(i))).size();
  EXPECT_GE(got, 3u);
  EXPECT_LE(p.buffered(), framed_size(kMaxPayload));
}

}  // namespace
}  // namespace rgnav::drivers::sick
