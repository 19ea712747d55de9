#include "scan_mapper/state_codec.h"

#include <cmath>

namespace rgnav::scan_mapper {
namespace {

constexpr uint64_t kMaxRanges = 100'000;
constexpr uint64_t kMaxPoints = 100'000;

bool finite(const Pose2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.theta()); }

}  // namespace

void ByteWriter::pose(const Pose2& p)
{
  put(p.x());
  put(p.y());
  put(p.theta());
}

void ByteWriter::matrix(const Eigen::Matrix3d& m)
{
  for (int i = 0; i < 9; ++i) put(m(i / 3, i % 3));
}

double ByteReader::finite()
{
  const auto v = get<double>();
  if (!std::isfinite(v)) throw CorruptState("non-finite number");
  return v;
}

Pose2 ByteReader::pose()
{
  const double x = finite(), y = finite();
  return Pose2(x, y, finite());
}

Eigen::Matrix3d ByteReader::matrix()
{
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = finite();
  return m;
}

uint64_t ByteReader::count(uint64_t max)
{
  const auto n = get<uint64_t>();
  if (n > max) throw CorruptState("implausible count " + std::to_string(n));
  return n;
}

void write_node(ByteWriter& w, const ScanNode& n)
{
  w.put(n.scan.utime), w.put(n.scan.scan_id), w.put(n.scan.angle_min), w.put(n.scan.angle_increment);
  w.put(n.scan.range_min), w.put(n.scan.range_max);
  w.put(static_cast<uint64_t>(n.scan.ranges.size()));
  for (float r : n.scan.ranges) w.put(r);
  w.pose(n.odom_from_base);
  w.put(n.path_m);
  w.put(static_cast<uint64_t>(n.points.size()));
  for (const auto& p : n.points) w.put(p.x()), w.put(p.y());
  write_estimate(w, n);
}

ScanNode read_node(ByteReader& r)
{
  ScanNode n;
  n.scan.utime = r.get<int64_t>();
  n.scan.scan_id = r.get<int64_t>();
  n.scan.angle_min = r.get<float>();
  n.scan.angle_increment = r.get<float>();
  n.scan.range_min = r.get<float>();
  n.scan.range_max = r.get<float>();
  n.scan.ranges.resize(r.count(kMaxRanges));
  for (auto& v : n.scan.ranges) {
    v = r.get<float>();
    if (!std::isfinite(v)) throw CorruptState("non-finite range");
  }
  if (!std::isfinite(n.scan.angle_min) || !std::isfinite(n.scan.angle_increment) || !std::isfinite(n.scan.range_min) ||
      !std::isfinite(n.scan.range_max))
    throw CorruptState("non-finite scan geometry");
  n.odom_from_base = r.pose();
  n.path_m = r.finite();
  n.points.resize(r.count(kMaxPoints));
  for (auto& p : n.points) {
    const double x = r.finite();
    p = Eigen::Vector2d(x, r.finite());
  }
  read_estimate(r, &n);
  return n;
}

void write_edge(ByteWriter& w, const PoseGraphEdge& e)
{
  w.put(static_cast<int32_t>(e.from)), w.put(static_cast<int32_t>(e.to));
  w.pose(e.from_from_to);
  w.matrix(e.information);
  w.put(static_cast<uint8_t>(e.robust));
}

PoseGraphEdge read_edge(ByteReader& r, uint64_t node_count)
{
  PoseGraphEdge e;
  e.from = r.get<int32_t>();
  e.to = r.get<int32_t>();
  e.from_from_to = r.pose();
  e.information = r.matrix();
  e.robust = r.get<uint8_t>() != 0;
  if (e.from < 0 || e.to < 0 || static_cast<uint64_t>(e.from) >= node_count || static_cast<uint64_t>(e.to) >= node_count)
    throw CorruptState("edge to a missing node");
  return e;
}

void write_estimate(ByteWriter& w, const ScanNode& n)
{
  w.pose(n.map_from_base);
  w.pose(n.published);
  w.matrix(n.covariance);
  w.put(static_cast<int32_t>(n.revision));
}

void read_estimate(ByteReader& r, ScanNode* n)
{
  n->map_from_base = r.pose();
  n->published = r.pose();
  n->covariance = r.matrix();
  n->revision = r.get<int32_t>();
  if (n->revision < 0) throw CorruptState("negative revision");
}

void check_finite(const ScanNode& n)
{
  if (!finite(n.map_from_base) || !finite(n.odom_from_base) || !finite(n.published) || !n.covariance.allFinite() ||
      !std::isfinite(n.path_m))
    throw CorruptState("scan " + std::to_string(n.scan.scan_id) + " has a non-finite pose or covariance");
}

void check_finite(const MapperState& state)
{
  for (const auto& n : state.nodes) check_finite(n);
  for (const auto& e : state.edges)
    if (!finite(e.from_from_to) || !e.information.allFinite()) throw CorruptState("pose graph edge is not finite");
}

}  // namespace rgnav::scan_mapper
