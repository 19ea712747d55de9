// A plain binary encoding for the processes' persisted state (the scan mapper's snapshot and
// journal records, the RG kernel's snapshot): fixed-width integers and IEEE doubles copied bit
// for bit in host order, little-endian on every rgnav target (the files never leave the
// machine). Bit copies, not text, because a restored process must continue exactly as the
// original would. The reader checks every length and count against what is left and every
// double it is asked for as finite, and throws CorruptBytes instead: a damaged payload that
// slipped past the file's CRC is refused, never half-loaded, and cannot crash a restore.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "geometry/pose2.h"

namespace rgnav::persist {

class CorruptBytes : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

class ByteWriter
{
 public:
  template <class T>
  void put(T v)
  {
    static_assert(std::is_arithmetic_v<T>, "plain numbers only");
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out_.append(b, sizeof(T));
  }
  void put(const Eigen::Vector2d& v)
  {
    put(v.x());
    put(v.y());
  }
  void put(const geometry::Pose2& p)
  {
    put(p.x());
    put(p.y());
    put(p.theta());
  }
  void put(const Eigen::Matrix3d& m)   // row by row
  {
    for (int i = 0; i < 9; ++i) put(m(i / 3, i % 3));
  }
  void put(const std::string& s)
  {
    put(static_cast<uint64_t>(s.size()));
    out_ += s;
  }
  void put_points(const std::vector<Eigen::Vector2d>& pts)
  {
    put(static_cast<uint64_t>(pts.size()));
    if (!pts.empty()) out_.append(reinterpret_cast<const char*>(pts.data()), pts.size() * sizeof(Eigen::Vector2d));
  }
  const std::string& bytes() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class ByteReader
{
 public:
  explicit ByteReader(const std::string& bytes) : s_(bytes) {}
  template <class T>
  T get()
  {
    static_assert(std::is_arithmetic_v<T>, "plain numbers only");
    need(sizeof(T));
    T v;
    std::memcpy(&v, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  double finite()
  {
    const double v = get<double>();
    if (!std::isfinite(v)) throw CorruptBytes("non-finite number at byte " + std::to_string(pos_ - sizeof v));
    return v;
  }
  Eigen::Vector2d vec()
  {
    const double x = finite();
    return {x, finite()};
  }
  geometry::Pose2 pose()
  {
    const double x = finite(), y = finite();
    return geometry::Pose2(x, y, finite());
  }
  Eigen::Matrix3d matrix()
  {
    Eigen::Matrix3d m;
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = finite();
    return m;
  }
  std::string str()
  {
    const uint64_t n = count(1);
    std::string v = s_.substr(pos_, n);
    pos_ += n;
    return v;
  }
  std::vector<Eigen::Vector2d> points()
  {
    const uint64_t n = count(sizeof(Eigen::Vector2d));
    std::vector<Eigen::Vector2d> pts(n);
    if (n) std::memcpy(static_cast<void*>(pts.data()), s_.data() + pos_, n * sizeof(Eigen::Vector2d));
    pos_ += n * sizeof(Eigen::Vector2d);
    return pts;
  }
  // A count of items of at least `item_bytes` each, refused if the rest cannot hold them or it
  // exceeds `max` (a bound the caller knows, e.g. the nodes a journal record may refer to).
  uint64_t count(size_t item_bytes, uint64_t max = std::numeric_limits<uint64_t>::max())
  {
    const uint64_t n = get<uint64_t>();
    const size_t at = pos_ - sizeof n;
    if (item_bytes > 0 && n > (s_.size() - pos_) / item_bytes)
      throw CorruptBytes("count " + std::to_string(n) + " at byte " + std::to_string(at) + " exceeds the data");
    if (n > max)
      throw CorruptBytes("count " + std::to_string(n) + " at byte " + std::to_string(at) + " exceeds " +
                         std::to_string(max));
    return n;
  }
  bool at_end() const { return pos_ == s_.size(); }

 private:
  void need(size_t n) const
  {
    if (s_.size() - pos_ < n) throw CorruptBytes("truncated at byte " + std::to_string(pos_));
  }
  const std::string& s_;
  size_t pos_ = 0;
};

}  // namespace rgnav::persist
