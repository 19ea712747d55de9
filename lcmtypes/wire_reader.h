// Bounds-checked reader over one LCM-encoded message, used by the generated validators
// (gen_validators.py). It never allocates and never reads past `len`.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace rgnav::wire {

class Reader
{
 public:
  Reader(const void* buf, size_t len, const char* type_name)
      : p_(static_cast<const uint8_t*>(buf)), len_(len), type_(type_name)
  {}

  void field(const char* name) { field_ = name; }

  bool fail(const char* what)
  {
    if (error_.empty())
      error_ = std::string(type_) + ": field '" + field_ + "' at byte " + std::to_string(pos_) +
               ": " + what;
    return false;
  }

  bool fingerprint(int64_t expected)
  {
    field_ = "<fingerprint>";
    int64_t got = 0;
    if (!i64(&got)) return false;
    return got == expected || fail("fingerprint mismatch (different message type or version)");
  }

  bool at_end() { field_ = "<end>"; return pos_ == len_ || fail("trailing bytes"); }

  // n elements of at least min_size bytes each must fit in what is left.
  bool fits(int64_t n, int64_t min_size)
  {
    if (n < 0) return fail("negative count");
    if (n > static_cast<int64_t>(len_ - pos_) / min_size) return fail("count exceeds message size");
    return true;
  }

  // Only after fits(n, size) succeeded for the same n and size.
  void skip(int64_t nbytes) { pos_ += static_cast<size_t>(nbytes); }

  bool u8(int64_t* v) { return read_int<uint8_t>(v); }
  bool i8(int64_t* v) { return read_int<int8_t>(v); }
  bool i16(int64_t* v) { return read_int<int16_t>(v); }
  bool i32(int64_t* v) { return read_int<int32_t>(v); }
  bool i64(int64_t* v) { return read_int<int64_t>(v); }

  bool f32()
  {
    int64_t bits = 0;
    if (!read_int<uint32_t>(&bits)) return false;
    float f;
    const auto u = static_cast<uint32_t>(bits);
    std::memcpy(&f, &u, sizeof f);
    return std::isfinite(f) || fail("float not finite");
  }

  bool f64()
  {
    uint64_t u = 0;
    if (!take(8)) return false;
    for (int i = 0; i < 8; ++i) u = (u << 8) | p_[pos_ - 8 + i];
    double d;
    std::memcpy(&d, &u, sizeof d);
    return std::isfinite(d) || fail("double not finite");
  }

  // LCM strings: int32 length including the terminating NUL, then the bytes.
  bool str()
  {
    int64_t n = 0;
    if (!i32(&n)) return false;
    if (n < 1) return fail("string length below 1");
    if (!take(static_cast<size_t>(n))) return false;
    if (p_[pos_ - 1] != 0) return fail("string not NUL-terminated");
    if (std::memchr(p_ + pos_ - n, 0, static_cast<size_t>(n - 1)) != nullptr)
      return fail("string has an embedded NUL");
    return true;
  }

  const std::string& error() const { return error_; }

 private:
  bool take(size_t n)
  {
    if (n > len_ - pos_) return fail("truncated");
    pos_ += n;
    return true;
  }

  template <class T>
  bool read_int(int64_t* v)
  {
    if (!take(sizeof(T))) return false;
    uint64_t u = 0;
    for (size_t i = 0; i < sizeof(T); ++i) u = (u << 8) | p_[pos_ - sizeof(T) + i];
    T t;
    using U = std::make_unsigned_t<T>;
    const auto narrowed = static_cast<U>(u);
    std::memcpy(&t, &narrowed, sizeof t);
    *v = static_cast<int64_t>(t);
    return true;
  }

  const uint8_t* p_;
  size_t len_;
  size_t pos_ = 0;
  const char* type_;
  const char* field_ = "";
  std::string error_;
};

}  // namespace rgnav::wire
