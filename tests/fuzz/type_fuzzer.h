// The corruption runner shared by the decode and the node-subscription fuzz tests: every
// corruption of valid sample messages aimed with the generated wire layout
// (rgnav_test_reflection.hpp), checked by the decode oracle (decode_checks.h). Two test files
// so that the template-heavy instantiations for every type compile in parallel (the nested
// sanitizer build of ctest fuzz_sanitized_build waits for them).
#pragma once

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

namespace rgnav::testing::fuzz {

using Bytes = std::vector<uint8_t>;

template <class T>
Bytes encoded(const T& msg)
{
  Bytes buf;
  std::string why;
  if (!bus::encode(msg, &buf, &why)) throw std::runtime_error("sample does not encode: " + why);
  return buf;
}

inline void put_int(Bytes& buf, size_t offset, int size, int64_t value)
{
  for (int i = 0; i < size; ++i)
    buf[offset + static_cast<size_t>(i)] = static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * (size - 1 - i)));
}

inline int64_t get_int(const Bytes& buf, size_t offset, int size)
{
  uint64_t u = 0;
  for (int i = 0; i < size; ++i) u = (u << 8) | buf[offset + static_cast<size_t>(i)];
  const int shift = 64 - 8 * size;
  return static_cast<int64_t>(u << shift) >> shift;
}

inline uint64_t seed_for(const std::string& name)
{
  if (const char* s = std::getenv("RGNAV_FUZZ_SEED"); s && *s) return std::stoull(s) ^ std::hash<std::string>{}(name);
  return std::hash<std::string>{}(name);
}

inline const char* outcome_name(DecodeOutcome o)
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

}  // namespace rgnav::testing::fuzz
