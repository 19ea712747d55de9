#include "scan_mapper/state_codec.h"

#include <cmath>

namespace rgnav::scan_mapper {
namespace {

constexpr uint64_t kMaxRanges = 100'000;
constexpr uint64_t kMaxPoints = 100'000;

bool finite(const Pose2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.theta()); }

}  // namespace

void write_node(persist::ByteWriter& w, const ScanNode& n)
{
  w.put(n.scan.utime), w.put(n.scan.scan_id);
  // The scan's header as float, as laser_scan_t carries it (the mapper's scans came over the bus
  // or were rounded like it: the values are floats held in doubles).
  w.put(static_cast<float>(n.scan.angle_min)), w.put(static_cast<float>(n.scan.angle_increment));
  w.put(static_cast<float>(n.scan.range_min)), w.put(static_cast<float>(n.scan.range_max));
  w.put(static_cast<uint64_t>(n.scan.ranges.size()));
  for (float r : n.scan.ranges) w.put(r);
  w.put(n.odom_from_base);
  w.put(n.path_m);
  w.put(static_cast<uint64_t>(n.points.size()));
  for (const auto& p : n.points) w.put(p.x()), w.put(p.y());
  write_estimate(w, n);
}

ScanNode read_node(persist::ByteReader& r)
{
  ScanNode n;
  n.scan.utime = r.get<int64_t>();
  n.scan.scan_id = r.get<int64_t>();
  n.scan.angle_min = r.get<float>();
  n.scan.angle_increment = r.get<float>();
  n.scan.range_min = r.get<float>();
  n.scan.range_max = r.get<float>();
  n.scan.ranges.resize(r.count(sizeof(float), kMaxRanges));
  for (auto& v : n.scan.ranges) {
    v = r.get<float>();
    if (!std::isfinite(v)) throw persist::CorruptBytes("non-finite range");
  }
  if (!std::isfinite(n.scan.angle_min) || !std::isfinite(n.scan.angle_increment) || !std::isfinite(n.scan.range_min) ||
      !std::isfinite(n.scan.range_max))
    throw persist::CorruptBytes("non-finite scan geometry");
  n.odom_from_base = r.pose();
  n.path_m = r.finite();
  n.points.resize(r.count(2 * sizeof(double), kMaxPoints));
  for (auto& p : n.points) {
    const double x = r.finite();
    p = Eigen::Vector2d(x, r.finite());
  }
  read_estimate(r, &n);
  return n;
}

void write_edge(persist::ByteWriter& w, const PoseGraphEdge& e)
{
  w.put(static_cast<int32_t>(e.from)), w.put(static_cast<int32_t>(e.to));
  w.put(e.from_from_to);
  w.put(e.information);
  w.put(static_cast<uint8_t>(e.robust));
}

PoseGraphEdge read_edge(persist::ByteReader& r, uint64_t node_count)
{
  PoseGraphEdge e;
  e.from = r.get<int32_t>();
  e.to = r.get<int32_t>();
  e.from_from_to = r.pose();
  e.information = r.matrix();
  e.robust = r.get<uint8_t>() != 0;
  if (e.from < 0 || e.to < 0 || static_cast<uint64_t>(e.from) >= node_count || static_cast<uint64_t>(e.to) >= node_count)
    throw persist::CorruptBytes("edge to a missing node");
  return e;
}

void write_estimate(persist::ByteWriter& w, const ScanNode& n)
{
  w.put(n.map_from_base);
  w.put(n.published);
  w.put(n.covariance);
  w.put(static_cast<int32_t>(n.revision));
}

void read_estimate(persist::ByteReader& r, ScanNode* n)
{
  n->map_from_base = r.pose();
  n->published = r.pose();
  n->covariance = r.matrix();
  n->revision = r.get<int32_t>();
  if (n->revision < 0) throw persist::CorruptBytes("negative revision");
}

void check_finite(const ScanNode& n)
{
  if (!finite(n.map_from_base) || !finite(n.odom_from_base) || !finite(n.published) || !n.covariance.allFinite() ||
      !std::isfinite(n.path_m))
    throw persist::CorruptBytes("scan " + std::to_string(n.scan.scan_id) + " has a non-finite pose or covariance");
}

void check_finite(const MapperState& state)
{
  for (const auto& n : state.nodes) check_finite(n);
  for (const auto& e : state.edges)
    if (!finite(e.from_from_to) || !e.information.allFinite())
      throw persist::CorruptBytes("pose graph edge is not finite");
}

}  // namespace rgnav::scan_mapper
