// Byte encoding of the mapper state and its parts (nodes, edges, estimates), shared by the
// snapshot file (mapper_state_io.h) and the journal records (mapper_store.h). Little-endian
// host layout (the files never leave the machine). Decoding checks every count against a
// bound and every number for finiteness, and throws CorruptState on anything else: a state
// that would poison the mapper is refused, never half-loaded.
#pragma once

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

class CorruptState : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

class ByteWriter
{
 public:
  template <class T>
  void put(const T& v)
  {
    static_assert(std::is_trivially_copyable_v<T>);
    buf_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void pose(const Pose2& p);
  void matrix(const Eigen::Matrix3d& m);
  const std::string& bytes() const { return buf_; }
  std::string take() { return std::move(buf_); }

 private:
  std::string buf_;
};

class ByteReader
{
 public:
  explicit ByteReader(const std::string& bytes) : buf_(bytes) {}
  template <class T>
  T get()
  {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    if (pos_ + sizeof v > buf_.size()) throw CorruptState("truncated");
    std::memcpy(&v, buf_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  double finite();  // a double that must be finite
  Pose2 pose();
  Eigen::Matrix3d matrix();
  uint64_t count(uint64_t max);
  bool at_end() const { return pos_ == buf_.size(); }

 private:
  const std::string& buf_;
  size_t pos_ = 0;
};

void write_node(ByteWriter& w, const ScanNode& n);
ScanNode read_node(ByteReader& r);  // normals are not stored: recomputed by the mapper
void write_edge(ByteWriter& w, const PoseGraphEdge& e);
PoseGraphEdge read_edge(ByteReader& r, uint64_t node_count);  // ends must be < node_count

// The parts of a node that change after it was added: estimate, covariance, publication.
void write_estimate(ByteWriter& w, const ScanNode& n);
void read_estimate(ByteReader& r, ScanNode* n);

// Throws CorruptState if a pose or covariance of the state is not finite: such a state is
// never written (it would be reloaded into every later run).
void check_finite(const MapperState& state);
void check_finite(const ScanNode& node);

}  // namespace rgnav::scan_mapper
