// Robustness of the decode path for every rgnav type: malformed input is refused with a reason
// and counted, never crashes, never allocates what the buffer cannot hold, and whatever is
// accepted round-trips byte for byte (decode_checks.h). Corruptions are aimed with the
// generated wire layout (rgnav_test_reflection.hpp): every count, string length, float, double,
// enum and boolean position of valid sample messages. Also built and run under ASan+UBSan
// (ctest fuzz_sanitized_*), and the same oracle drives the libFuzzer target.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <type_traits>

#include "bus/fake_bus.h"
#include "decode_checks.h"
#include "rgnav_test_reflection.hpp"
#include "runtime/node.h"
#include "sample_messages.h"

namespace rgnav::testing {
namespace {

using Bytes = std::vector<uint8_t>;

template <class T>
Bytes encoded(const T& msg)
{
  Bytes buf;
  std::string why;
  if (!bus::encode(msg, &buf, &why)) throw std::runtime_error("sample does not encode: " + why);
  return buf;
}

void put_int(Bytes& buf, size_t offset, int size, int64_t value)
{
  for (int i = 0; i < size; ++i)
    buf[offset + static_cast<size_t>(i)] = static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * (size - 1 - i)));
}

int64_t get_int(const Bytes& buf, size_t offset, int size)
{
  uint64_t u = 0;
  for (int i = 0; i < size; ++i) u = (u << 8) | buf[offset + static_cast<size_t>(i)];
  const int shift = 64 - 8 * size;
  return static_cast<int64_t>(u << shift) >> shift;
}

uint64_t seed_for(const std::string& name)
{
  if (const char* s = std::getenv("RGNAV_FUZZ_SEED"); s && *s) return std::stoull(s) ^ std::hash<std::string>{}(name);
  return std::hash<std::string>{}(name);
}

const char* outcome_name(DecodeOutcome o)
{
  switch (o) {
    case DecodeOutcome::kRejected: return "rejected";
    case DecodeOutcome::kAccepted: return "accepted";
    case DecodeOutcome::kAcceptedButNotCanonical: return "accepted but does not round-trip";
    case DecodeOutcome::kRejectedWithoutReason: return "rejected without a reason";
  }
  return "?";
}

// Runs all corruptions of one type and keeps the buffers that must be refused, so the Node
// test can push the very same ones through a subscription.
template <class T>
class TypeFuzzer
{
 public:
  explicit TypeFuzzer(std::string name) : name_(std::move(name)), rng_(seed_for(name_)) {}

  void run()
  {
    for (uint32_t variant = 0; variant < 4; ++variant) {
      const Bytes valid = encoded(sample<T>(variant));
      expect(valid, DecodeOutcome::kAccepted, "valid sample");
      valid_.push_back(valid);
      truncations(valid);
      trailing_bytes(valid);
      fingerprints(valid);
      aimed(valid);
      bit_flips(valid);
      overwrites(valid);
    }
    random_buffers(valid_.front());
  }

  const std::vector<Bytes>& must_reject() const { return must_reject_; }
  const std::vector<Bytes>& valid() const { return valid_; }
  size_t cases() const { return cases_; }
  size_t rejected() const { return rejected_; }

 private:
  // Must be refused (with a reason).
  void reject(const Bytes& buf, const std::string& what)
  {
    expect(buf, DecodeOutcome::kRejected, what);
    if (must_reject_.size() < 4000) must_reject_.push_back(buf);
  }

  // Anything but a crash or a non-canonical acceptance.
  void survive(const Bytes& buf, const std::string& what)
  {
    const auto o = check_decode<T>(buf.data(), buf.size());
    ++cases_;
    rejected_ += o == DecodeOutcome::kRejected;
    EXPECT_TRUE(o == DecodeOutcome::kRejected || o == DecodeOutcome::kAccepted)
        << name_ << ": " << what << ": " << outcome_name(o);
  }

  void expect(const Bytes& buf, DecodeOutcome want, const std::string& what)
  {
    const auto o = check_decode<T>(buf.data(), buf.size());
    ++cases_;
    rejected_ += o == DecodeOutcome::kRejected;
    EXPECT_EQ(o, want) << name_ << ": " << what << ": " << outcome_name(o) << " (" << buf.size() << " bytes)";
  }

  void truncations(const Bytes& valid)
  {
    for (size_t len = 0; len < valid.size(); ++len)
      reject(Bytes(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(len)),
             "truncated to " + std::to_string(len));
  }

  void trailing_bytes(const Bytes& valid)
  {
    for (size_t extra : {1, 8, 64}) {
      Bytes b = valid;
      b.resize(valid.size() + extra, 0);
      reject(b, std::to_string(extra) + " trailing bytes");
    }
  }

  void fingerprints(const Bytes& valid)
  {
    for (int bit = 0; bit < 64; ++bit) {
      Bytes b = valid;
      b[static_cast<size_t>(bit / 8)] ^= static_cast<uint8_t>(1u << (bit % 8));
      reject(b, "fingerprint bit " + std::to_string(bit) + " flipped");
    }
  }

  void aimed(const Bytes& valid)
  {
    const auto slots = wire_layout<T>(valid.data(), valid.size());
    for (const auto& s : slots) {
      const std::string at = s.field + " @" + std::to_string(s.offset);
      auto with = [&](int64_t v) {
        Bytes b = valid;
        put_int(b, s.offset, s.size, v);
        return b;
      };
      const int64_t cur = get_int(valid, s.offset, s.size);
      switch (s.kind) {
        case SlotKind::kCount:
          for (int64_t v : {int64_t{-1}, int64_t{INT32_MIN}, int64_t{INT32_MAX}, int64_t{0x40000000},
                            static_cast<int64_t>(valid.size())})
            if (v != cur) reject(with(v), "count " + at + " = " + std::to_string(v));
          for (int64_t v : {cur + 1, cur - 1, int64_t{0}})
            if (v != cur) survive(with(v), "count " + at + " = " + std::to_string(v));
          break;
        case SlotKind::kStringLength: {
          for (int64_t v : {int64_t{0}, int64_t{-1}, int64_t{INT32_MIN}, int64_t{INT32_MAX},
                            static_cast<int64_t>(valid.size())})
            reject(with(v), "string length " + at + " = " + std::to_string(v));
          for (int64_t v : {cur + 1, cur - 1}) survive(with(v), "string length " + at + " = " + std::to_string(v));
          Bytes unterminated = valid;
          unterminated[s.offset + 4 + static_cast<size_t>(cur) - 1] = 'x';
          reject(unterminated, "string " + at + " without NUL");
          if (cur > 1) {
            Bytes embedded = valid;
            embedded[s.offset + 4] = 0;
            reject(embedded, "string " + at + " with embedded NUL");
          }
          break;
        }
        case SlotKind::kFloat:
          for (uint32_t bits : {0x7fc00000u, 0xffc00000u, 0x7f800001u, 0x7f800000u, 0xff800000u})
            reject(with(static_cast<int32_t>(bits)), "float " + at + " non-finite");
          break;
        case SlotKind::kDouble:
          for (uint64_t bits : {0x7ff8000000000000ull, 0xfff8000000000000ull, 0x7ff0000000000001ull,
                                0x7ff0000000000000ull, 0xfff0000000000000ull})
            reject(with(static_cast<int64_t>(bits)), "double " + at + " non-finite");
          break;
        case SlotKind::kEnum:
        case SlotKind::kBoolean: {
          const int64_t lo = -(int64_t{1} << (8 * s.size - 1)), hi = (int64_t{1} << (8 * s.size - 1)) - 1;
          const auto [mn, mx] = std::minmax_element(s.allowed.begin(), s.allowed.end());
          for (int64_t v : {*mx + 1, *mn - 1, hi, lo, int64_t{-1}}) {
            if (v < lo || v > hi || std::find(s.allowed.begin(), s.allowed.end(), v) != s.allowed.end()) continue;
            reject(with(v), std::string(s.kind == SlotKind::kEnum ? "enum " : "boolean ") + at + " = " +
                                std::to_string(v));
          }
          break;
        }
      }
    }
  }

  void bit_flips(const Bytes& valid)
  {
    // Every bit of the first 256 bytes (headers, counts, strings), then random bits beyond.
    const size_t head = std::min<size_t>(valid.size(), 256);
    for (size_t bit = 0; bit < 8 * head; ++bit) {
      Bytes b = valid;
      b[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      survive(b, "bit " + std::to_string(bit) + " flipped");
    }
    for (int i = 0; valid.size() > head && i < 256; ++i) {
      const size_t bit = 8 * head + rng_() % (8 * (valid.size() - head));
      Bytes b = valid;
      b[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      survive(b, "bit " + std::to_string(bit) + " flipped");
    }
  }

  void overwrites(const Bytes& valid)
  {
    for (int i = 0; valid.size() > 8 && i < 100; ++i) {
      Bytes b = valid;
      const size_t n = 1 + rng_() % 4;
      const size_t at = 8 + rng_() % (valid.size() - 8);
      for (size_t k = at; k < std::min(b.size(), at + n); ++k) b[k] = static_cast<uint8_t>(rng_());
      survive(b, "bytes overwritten at " + std::to_string(at));
    }
  }

  void random_buffers(const Bytes& valid)
  {
    for (int i = 0; i < 200; ++i) {
      Bytes b(rng_() % (2 * valid.size() + 16));
      for (auto& x : b) x = static_cast<uint8_t>(rng_());
      if (i % 2 && b.size() >= 8) std::copy(valid.begin(), valid.begin() + 8, b.begin());  // right fingerprint
      survive(b, "random buffer " + std::to_string(i));
    }
  }

  std::string name_;
  std::mt19937_64 rng_;
  std::vector<Bytes> valid_;
  std::vector<Bytes> must_reject_;
  size_t cases_ = 0;
  size_t rejected_ = 0;
};

template <class T>
void fuzz_decode(const char* name)
{
  TypeFuzzer<T> f(name);
  f.run();
  ::testing::Test::RecordProperty("cases", static_cast<int>(f.cases()));
  ::testing::Test::RecordProperty("rejected", static_cast<int>(f.rejected()));
}

// One test per type: DecodeFuzz.laser_scan_t, ...
#define RGNAV_DECODE_TEST(T) \
  TEST(DecodeFuzz, T) { fuzz_decode<T>(#T); }
RGNAV_FOR_EACH_TYPE(RGNAV_DECODE_TEST)
#undef RGNAV_DECODE_TEST

// Through a runtime::Node subscription: the same corrupt buffers are dropped and counted, valid
// ones interleaved with them reach the handler unchanged, and the heartbeat reports the drops.
template <class T>
void fuzz_node(const char* name)
{
  TypeFuzzer<T> f(name);
  f.run();
  runtime::NodeOptions options;
  options.name = "fuzz_node";
  auto fake = std::make_unique<bus::FakeBus>();
  bus::FakeBus* bus = fake.get();
  runtime::Node node(options, std::move(fake));
  std::vector<std::string> received;
  node.subscribe<T>("IN", [&](const T& msg) { received.push_back(to_json(msg)); });

  std::vector<std::string> expected;
  size_t next_valid = 0;
  for (size_t i = 0; i < f.must_reject().size(); ++i) {
    const auto& bad = f.must_reject()[i];
    bus->publish("IN", bad.data(), bad.size());
    if (i % 50 == 0) {
      const Bytes& good = f.valid()[next_valid++ % f.valid().size()];
      T decoded;
      std::string why;
      ASSERT_TRUE(bus::decode<T>(good.data(), good.size(), &decoded, &why)) << why;
      expected.push_back(to_json(decoded));
      bus->publish("IN", good.data(), good.size());
    }
  }
  EXPECT_EQ(received, expected) << name;
  EXPECT_EQ(node.drops().total(), static_cast<int64_t>(f.must_reject().size())) << name;
  EXPECT_EQ(node.drops().on_channel("IN"), static_cast<int64_t>(f.must_reject().size())) << name;
  EXPECT_EQ(node.messages_in(), static_cast<int64_t>(expected.size())) << name;

  node.publish_heartbeat();
  const auto beats = bus->published_on("HEARTBEAT");
  ASSERT_FALSE(beats.empty());
  heartbeat_t hb;
  std::string why;
  ASSERT_TRUE(bus::decode<heartbeat_t>(beats.back().data.data(), beats.back().data.size(), &hb, &why)) << why;
  EXPECT_EQ(hb.messages_dropped, static_cast<int64_t>(f.must_reject().size()));
  EXPECT_EQ(hb.messages_in, static_cast<int64_t>(expected.size()));
}

#define RGNAV_NODE_TEST(T) \
  TEST(NodeSubscriptionFuzz, T) { fuzz_node<T>(#T); }
RGNAV_FOR_EACH_MESSAGE_TYPE(RGNAV_NODE_TEST)
#undef RGNAV_NODE_TEST

// A message of one type offered as another is refused on the fingerprint.
template <class T>
void refuse_all_others(const char* name)
{
  const Bytes bytes = encoded(sample<T>(1));
  auto as = [&](auto tag, const char* other) {
    using U = decltype(tag);
    if (std::is_same_v<T, U>) return;
    EXPECT_EQ(check_decode<U>(bytes.data(), bytes.size()), DecodeOutcome::kRejected) << name << " as " << other;
  };
#define RGNAV_AS(U) as(U{}, #U);
  RGNAV_FOR_EACH_TYPE(RGNAV_AS)
#undef RGNAV_AS
}

TEST(CrossTypeFuzz, EveryTypeRefusesEveryOtherType)
{
#define RGNAV_CROSS(T) refuse_all_others<T>(#T);
  RGNAV_FOR_EACH_TYPE(RGNAV_CROSS)
#undef RGNAV_CROSS
}

// Semantic checks (msg::semantically_valid) beyond the wire format, through a subscription:
// encoded with lcm-gen directly, as a buggy or hostile sender would.
template <class T>
Bytes raw_encode(const T& msg)
{
  Bytes b(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

TEST(NodeSubscriptionFuzz, SemanticallyInvalidMessagesAreDroppedAndCounted)
{
  runtime::NodeOptions options;
  options.name = "semantic";
  auto fake = std::make_unique<bus::FakeBus>();
  bus::FakeBus* bus = fake.get();
  runtime::Node node(options, std::move(fake));
  int scans = 0, images = 0, cmds = 0, grids = 0, goals = 0, trajectories = 0, regions = 0;
  node.subscribe<laser_scan_t>("SCAN", [&](const laser_scan_t&) { ++scans; });
  node.subscribe<image_t>("IMAGE", [&](const image_t&) { ++images; });
  node.subscribe<velocity_cmd_t>("CMD", [&](const velocity_cmd_t&) { ++cmds; });
  node.subscribe<obstacle_grid_t>("GRID", [&](const obstacle_grid_t&) { ++grids; });
  node.subscribe<nav_goal_t>("GOAL", [&](const nav_goal_t&) { ++goals; });
  node.subscribe<trajectory_t>("TRAJ", [&](const trajectory_t&) { ++trajectories; });
  node.subscribe<region_t>("REGION", [&](const region_t&) { ++regions; });

  std::vector<std::pair<std::string, Bytes>> bad;
  {
    auto m = sample<laser_scan_t>(0);
    m.scan_id = 0;
    bad.push_back({"SCAN", raw_encode(m)});
    m = sample<laser_scan_t>(0);
    m.ranges[5] = -1.f;
    bad.push_back({"SCAN", raw_encode(m)});
    m = sample<laser_scan_t>(0);
    m.nintensities = 3;
    m.intensities.assign(3, 1.f);
    bad.push_back({"SCAN", raw_encode(m)});
    m = sample<laser_scan_t>(0);
    m.angle_increment = 0.1f;  // 181 beams over 18 rad
    bad.push_back({"SCAN", raw_encode(m)});
  }
  {
    auto m = sample<image_t>(0);
    m.height += 1;  // size no longer row_stride * height
    bad.push_back({"IMAGE", raw_encode(m)});
    m = sample<image_t>(2);  // JPEG without SOI marker
    m.data[0] = 0;
    bad.push_back({"IMAGE", raw_encode(m)});
  }
  {
    auto m = sample<velocity_cmd_t>(0);
    m.v = 50;
    bad.push_back({"CMD", raw_encode(m)});
    m = sample<velocity_cmd_t>(0);
    m.deadline_us = 0;
    bad.push_back({"CMD", raw_encode(m)});
  }
  {
    auto m = sample<obstacle_grid_t>(1);
    m.cells.assign(m.cells.size(), 101);
    if (!m.cells.empty()) bad.push_back({"GRID", raw_encode(m)});
  }
  {
    auto m = sample<nav_goal_t>(0);
    m.position_tolerance = 0;
    bad.push_back({"GOAL", raw_encode(m)});
  }
  {
    auto m = sample<trajectory_t>(0);
    m.a_max = -1;
    bad.push_back({"TRAJ", raw_encode(m)});
  }
  {
    auto m = sample<region_t>(0);
    m.freespace_nbytes += 1;
    m.freespace.push_back(0);
    bad.push_back({"REGION", raw_encode(m)});
  }
  for (const auto& [channel, bytes] : bad) bus->publish(channel, bytes.data(), bytes.size());
  EXPECT_EQ(scans + images + cmds + grids + goals + trajectories + regions, 0);
  EXPECT_EQ(node.drops().total(), static_cast<int64_t>(bad.size()));
  EXPECT_EQ(node.drops().on_channel("SCAN"), 4);

  // The valid originals still pass.
  for (auto [channel, bytes] : std::vector<std::pair<std::string, Bytes>>{
           {"SCAN", raw_encode(sample<laser_scan_t>(0))}, {"IMAGE", raw_encode(sample<image_t>(2))},
           {"CMD", raw_encode(sample<velocity_cmd_t>(0))}, {"GOAL", raw_encode(sample<nav_goal_t>(0))}})
    bus->publish(channel, bytes.data(), bytes.size());
  EXPECT_EQ(scans, 1);
  EXPECT_EQ(images, 1);
  EXPECT_EQ(cmds, 1);
  EXPECT_EQ(goals, 1);
  EXPECT_EQ(node.drops().total(), static_cast<int64_t>(bad.size()));
}

// The harness itself can tell accepted from refused.
TEST(DecodeFuzzHarness, OracleCanFail)
{
  const Bytes valid = encoded(sample<laser_scan_t>(0));
  EXPECT_EQ(check_decode<laser_scan_t>(valid.data(), valid.size()), DecodeOutcome::kAccepted);
  EXPECT_EQ(check_decode<laser_scan_t>(valid.data(), valid.size() - 1), DecodeOutcome::kRejected);
  EXPECT_EQ(check_decode<odometry_t>(valid.data(), valid.size()), DecodeOutcome::kRejected);
}

}  // namespace
}  // namespace rgnav::testing
