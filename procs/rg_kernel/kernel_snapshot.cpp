// Binary snapshot of the RG kernel's state (RgKernel::save_state / restore_state and the
// RegionBuilder parts): everything needed to continue identically — the map as it stands, each
// region's scans and the caches derived from them incrementally (merged line map, carved
// cells, circle observations), and the kernel's bookkeeping. Doubles are copied bit for bit.
#include <algorithm>
#include <stdexcept>

#include "procs/rg_kernel/region_builder.h"
#include "procs/rg_kernel/rg_kernel.h"

namespace rgnav::rg_kernel {

using Eigen::Vector2d;

namespace {

constexpr uint32_t kKernelMagic = 0x4b475231;   // "1RGK"
// 2: each builder also keeps its points seen through (seen_through.h). Format 1 still loads: they
// are found afresh at the builder's next rebuild.
constexpr uint32_t kFormat = 2;

void put_segments(persist::ByteWriter& w, const std::vector<rgmap::LineSegment>& segs)
{
  w.put(static_cast<uint64_t>(segs.size()));
  for (const auto& s : segs) {
    w.put(s.a);
    w.put(s.b);
    w.put(s.sigma);
    w.put(static_cast<int32_t>(s.support));
  }
}

std::vector<rgmap::LineSegment> get_segments(persist::ByteReader& r)
{
  std::vector<rgmap::LineSegment> segs(r.count(36));
  for (auto& s : segs) {
    s.a = r.vec();
    s.b = r.vec();
    s.sigma = r.get<double>();
    s.support = r.get<int32_t>();
  }
  return segs;
}

void put_map(persist::ByteWriter& w, const rgmap::RgMap& m)
{
  w.put(m.current_region);
  w.put(m.version);
  w.put(m.last_scan_id);
  w.put(m.utime);
  w.put(m.next_region_id());
  w.put(m.next_gateway_id());
  w.put(static_cast<uint64_t>(m.regions().size()));
  for (const auto& [id, r] : m.regions()) {
    w.put(r.id);
    w.put(r.name);
    w.put(static_cast<int8_t>(r.state));
    w.put(r.merged_into);
    w.put(r.utime);
    w.put(r.map_from_region);
    put_segments(w, r.segments);
    w.put(static_cast<uint64_t>(r.objects.size()));
    for (const auto& o : r.objects) {
      w.put(o.id);
      w.put(static_cast<int8_t>(o.shape));
      w.put(o.center);
      w.put(o.length);
      w.put(o.width);
      w.put(o.confidence);
    }
    w.put(static_cast<uint64_t>(r.objects3d.size()));
    for (const auto& o : r.objects3d) {
      w.put(o.id);
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j) w.put(o.corners(i, j));
      for (int j = 0; j < 3; ++j) w.put(o.normal(j));
      w.put(o.width);
      w.put(o.height);
      w.put(o.confidence);
      w.put(o.kind);
    }
    w.put(r.bbox_min);
    w.put(r.bbox_max);
    w.put(r.freespace.resolution());
    w.put(r.freespace.region_from_grid());
    w.put(static_cast<int32_t>(r.freespace.width()));
    w.put(static_cast<int32_t>(r.freespace.height()));
    w.put(std::string(r.freespace.bytes().begin(), r.freespace.bytes().end()));
    w.put(r.accuracy);
    w.put(r.completeness);
    w.put(static_cast<int32_t>(r.nscans));
  }
  w.put(static_cast<uint64_t>(m.gateways().size()));
  for (const auto& [id, g] : m.gateways()) {
    w.put(g.id);
    w.put(static_cast<int8_t>(g.cls));
    w.put(g.region_a);
    w.put(g.region_b);
    w.put(g.region_a_from_region_b);
    w.put_points(g.gateway_points);
    w.put_points(g.crossing_points);
    w.put(static_cast<uint64_t>(g.traversal_directions.size()));
    for (const double d : g.traversal_directions) w.put(d);
    w.put(static_cast<int32_t>(g.traversals));
    w.put(g.mean_traversal_time);
    w.put(static_cast<uint8_t>(g.neutralized));
  }
}

rgmap::RgMap get_map(persist::ByteReader& rd)
{
  rgmap::RgMap m;
  m.current_region = rd.get<int64_t>();
  m.version = rd.get<int64_t>();
  m.last_scan_id = rd.get<int64_t>();
  m.utime = rd.get<int64_t>();
  const int64_t next_region = rd.get<int64_t>(), next_gateway = rd.get<int64_t>();
  const uint64_t nregions = rd.count(64);
  for (uint64_t k = 0; k < nregions; ++k) {
    rgmap::Region r;
    r.id = rd.get<int64_t>();
    r.name = rd.str();
    r.state = static_cast<rgmap::Region::State>(rd.get<int8_t>());
    r.merged_into = rd.get<int64_t>();
    r.utime = rd.get<int64_t>();
    r.map_from_region = rd.pose();
    r.segments = get_segments(rd);
    r.objects.resize(rd.count(48));
    for (auto& o : r.objects) {
      o.id = rd.get<int64_t>();
      o.shape = static_cast<rgmap::Object2d::Shape>(rd.get<int8_t>());
      o.center = rd.pose();
      o.length = rd.get<double>();
      o.width = rd.get<double>();
      o.confidence = rd.get<double>();
    }
    r.objects3d.resize(rd.count(100));
    for (auto& o : r.objects3d) {
      o.id = rd.get<int64_t>();
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j) o.corners(i, j) = rd.get<double>();
      for (int j = 0; j < 3; ++j) o.normal(j) = rd.get<double>();
      o.width = rd.get<double>();
      o.height = rd.get<double>();
      o.confidence = rd.get<double>();
      o.kind = rd.get<int8_t>();
    }
    r.bbox_min = rd.vec();
    r.bbox_max = rd.vec();
    const double res = rd.get<double>();
    const geometry::Pose2 region_from_grid = rd.pose();
    const int32_t w = rd.get<int32_t>(), h = rd.get<int32_t>();
    const std::string bits = rd.str();
    if (w > 0 || h > 0 || !bits.empty())
      r.freespace = rgmap::FreespaceBitmap(res, region_from_grid, w, h, std::vector<uint8_t>(bits.begin(), bits.end()));
    r.accuracy = rd.get<double>();
    r.completeness = rd.get<double>();
    r.nscans = rd.get<int32_t>();
    m.insert_region(std::move(r));
  }
  const uint64_t ngateways = rd.count(64);
  for (uint64_t k = 0; k < ngateways; ++k) {
    rgmap::Gateway g;
    g.id = rd.get<int64_t>();
    g.cls = static_cast<rgmap::GatewayClass>(rd.get<int8_t>());
    g.region_a = rd.get<int64_t>();
    g.region_b = rd.get<int64_t>();
    g.region_a_from_region_b = rd.pose();
    g.gateway_points = rd.points();
    g.crossing_points = rd.points();
    g.traversal_directions.resize(rd.count(8));
    for (auto& d : g.traversal_directions) d = rd.get<double>();
    g.traversals = rd.get<int32_t>();
    g.mean_traversal_time = rd.get<double>();
    g.neutralized = rd.get<uint8_t>() != 0;
    m.insert_gateway(std::move(g));
  }
  m.set_next_ids(next_region, next_gateway);
  return m;
}

}  // namespace

void RegionBuilder::save(persist::ByteWriter& w, const SharedPoints& shared_points) const
{
  w.put(static_cast<uint64_t>(scans_.size()));
  for (const auto& [id, s] : scans_) {
    w.put(s.scan_id);
    w.put(s.utime);
    w.put(s.revision);
    w.put(s.region_from_laser);
    const auto* shared = shared_points ? shared_points(id) : nullptr;
    const bool same = shared && *shared == s.laser_points;
    w.put(static_cast<uint8_t>(same));
    if (!same) w.put_points(s.laser_points);
  }
  w.put(static_cast<uint64_t>(gateway_lines_.size()));
  for (const auto& [a, b] : gateway_lines_) {
    w.put(a);
    w.put(b);
  }
  w.put(static_cast<uint8_t>(stale_));
  put_segments(w, segments_);
  // Cells sorted: the same state gives the same bytes.
  std::vector<uint64_t> cells(free_cells_.begin(), free_cells_.end());
  std::sort(cells.begin(), cells.end());
  w.put(static_cast<uint64_t>(cells.size()));
  for (const uint64_t c : cells) w.put(c);
  w.put(lo_);
  w.put(hi_);
  w.put(static_cast<uint64_t>(circle_observations_.size()));
  for (const auto& [id, obs] : circle_observations_) {
    w.put(id);
    w.put(static_cast<uint64_t>(obs.size()));
    for (const auto& o : obs) {
      w.put(o.center);
      w.put(o.radius);
    }
  }
  w.put(static_cast<uint8_t>(seen_through_valid_));
  w.put(static_cast<uint8_t>(holds_seen_through_));
  w.put(scans_at_rebuild_);
  using Flags = std::map<int64_t, std::vector<char>>;
  for (const Flags* seen : {static_cast<const Flags*>(&seen_through_), &seen_elsewhere_}) {
    w.put(static_cast<uint64_t>(seen->size()));
    for (const auto& [id, flags] : *seen) {
      w.put(id);
      w.put(static_cast<uint64_t>(flags.size()));
      for (const char f : flags) w.put(static_cast<uint8_t>(f));
    }
  }
}

void RegionBuilder::load(persist::ByteReader& r, const SharedPoints& shared_points, uint32_t format)
{
  scans_.clear();
  const uint64_t nscans = r.count(45);
  for (uint64_t k = 0; k < nscans; ++k) {
    StoredScan s;
    s.scan_id = r.get<int64_t>();
    s.utime = r.get<int64_t>();
    s.revision = r.get<int32_t>();
    s.region_from_laser = r.pose();
    if (r.get<uint8_t>()) {
      const auto* shared = shared_points ? shared_points(s.scan_id) : nullptr;
      if (!shared)
        throw persist::CorruptBytes("scan " + std::to_string(s.scan_id) + " refers to points the snapshot lacks");
      s.laser_points = *shared;
    } else {
      s.laser_points = r.points();
    }
    const int64_t id = s.scan_id;
    scans_.emplace(id, std::move(s));
  }
  gateway_lines_.resize(r.count(32));
  for (auto& [a, b] : gateway_lines_) {
    a = r.vec();
    b = r.vec();
  }
  stale_ = r.get<uint8_t>() != 0;
  segments_ = get_segments(r);
  free_cells_.clear();
  const uint64_t ncells = r.count(8);
  free_cells_.reserve(ncells);
  for (uint64_t k = 0; k < ncells; ++k) free_cells_.insert(r.get<uint64_t>());
  lo_ = r.vec();
  hi_ = r.vec();
  circle_observations_.clear();
  const uint64_t nobs = r.count(16);
  for (uint64_t k = 0; k < nobs; ++k) {
    const int64_t id = r.get<int64_t>();
    std::vector<CircleObservation> obs(r.count(24));
    for (auto& o : obs) {
      o.center = r.vec();
      o.radius = r.get<double>();
    }
    circle_observations_[id] = std::move(obs);
  }
  seen_through_.clear();
  seen_elsewhere_.clear();
  seen_scans_.clear();
  if (format < 2) {
    // Found afresh from all the scans at the next rebuild (a stale line map is rebuilt anyway).
    seen_through_valid_ = false;
    holds_seen_through_ = !scans_.empty();
    scans_at_rebuild_ = 0;
    return;
  }
  seen_through_valid_ = r.get<uint8_t>() != 0;
  holds_seen_through_ = r.get<uint8_t>() != 0;
  scans_at_rebuild_ = r.get<uint64_t>();
  using Flags = std::map<int64_t, std::vector<char>>;
  for (Flags* seen : {&seen_through_, &seen_elsewhere_}) {
    const uint64_t nseen = r.count(16);
    for (uint64_t k = 0; k < nseen; ++k) {
      const int64_t id = r.get<int64_t>();
      std::vector<char> flags(r.count(1));
      for (auto& f : flags) f = static_cast<char>(r.get<uint8_t>() != 0);
      (*seen)[id] = std::move(flags);
    }
  }
}

void RgKernel::save_state(persist::ByteWriter& w) const
{
  w.put(kKernelMagic);
  w.put(kFormat);
  put_map(w, map_);
  // The scans' points once (the builders refer to them); then each builder.
  w.put(static_cast<uint64_t>(scan_inputs_.size()));
  for (const auto& [id, s] : scan_inputs_) {
    w.put(s.scan_id);
    w.put(s.utime);
    w.put(s.revision);
    w.put(s.map_from_base);
    w.put(s.base_from_laser);
    w.put_points(s.laser_points);
  }
  const auto shared = [this](int64_t scan_id) -> const std::vector<Vector2d>* {
    auto it = scan_inputs_.find(scan_id);
    return it == scan_inputs_.end() ? nullptr : &it->second.laser_points;
  };
  w.put(static_cast<uint64_t>(builders_.size()));
  for (const auto& [id, b] : builders_) {
    w.put(id);
    b.save(w, shared);
  }
  w.put(static_cast<uint64_t>(region_of_scan_.size()));
  for (const auto& [scan, region] : region_of_scan_) {
    w.put(scan);
    w.put(region);
  }
  w.put(static_cast<uint64_t>(entered_utime_.size()));
  for (const auto& [track, t] : entered_utime_) {
    w.put(track);
    w.put(t);
  }
  w.put(static_cast<int32_t>(scans_since_entering_));
  w.put(static_cast<uint64_t>(dirty_.size()));
  for (const int64_t id : dirty_) w.put(id);
}

std::string RgKernel::snapshot() const
{
  persist::ByteWriter w;
  save_state(w);
  return w.take();
}

void RgKernel::restore_state(persist::ByteReader& r)
{
  if (r.get<uint32_t>() != kKernelMagic) throw persist::CorruptBytes("not an RG kernel state");
  const uint32_t format = r.get<uint32_t>();
  if (format < 1 || format > kFormat)
    throw persist::CorruptBytes("RG kernel state format " + std::to_string(format) + ", this build reads 1 to " +
                                std::to_string(kFormat));
  rgmap::RgMap map;
  try {
    map = get_map(r);
  } catch (const std::invalid_argument& e) {
    throw persist::CorruptBytes(std::string("map: ") + e.what());
  }
  std::map<int64_t, ScanInput> inputs;
  const uint64_t ninputs = r.count(68);
  for (uint64_t k = 0; k < ninputs; ++k) {
    ScanInput s;
    s.scan_id = r.get<int64_t>();
    s.utime = r.get<int64_t>();
    s.revision = r.get<int32_t>();
    s.map_from_base = r.pose();
    s.base_from_laser = r.pose();
    s.laser_points = r.points();
    const int64_t id = s.scan_id;
    inputs.emplace(id, std::move(s));
  }
  const auto shared = [&inputs](int64_t scan_id) -> const std::vector<Vector2d>* {
    auto it = inputs.find(scan_id);
    return it == inputs.end() ? nullptr : &it->second.laser_points;
  };
  std::map<int64_t, RegionBuilder> builders;
  const uint64_t nbuilders = r.count(16);
  for (uint64_t k = 0; k < nbuilders; ++k) {
    const int64_t id = r.get<int64_t>();
    if (!map.region(id)) throw persist::CorruptBytes("builder for unknown region " + std::to_string(id));
    RegionBuilder b(options_.build);
    b.load(r, shared, format);
    builders.emplace(id, std::move(b));
  }
  std::map<int64_t, int64_t> region_of_scan;
  const uint64_t nscans = r.count(16);
  for (uint64_t k = 0; k < nscans; ++k) {
    const int64_t scan = r.get<int64_t>();
    region_of_scan[scan] = r.get<int64_t>();
  }
  std::map<int64_t, int64_t> entered;
  const uint64_t nentered = r.count(16);
  for (uint64_t k = 0; k < nentered; ++k) {
    const int64_t track = r.get<int64_t>();
    entered[track] = r.get<int64_t>();
  }
  const int32_t since = r.get<int32_t>();
  std::set<int64_t> dirty;
  const uint64_t ndirty = r.count(8);
  for (uint64_t k = 0; k < ndirty; ++k) dirty.insert(r.get<int64_t>());
  if (map.current_region != 0 && !builders.count(map.current_region))
    throw persist::CorruptBytes("current region " + std::to_string(map.current_region) + " has no scans");
  if (!r.at_end()) throw persist::CorruptBytes("trailing bytes after the RG kernel state");
  // All read and checked: commit.
  map_ = std::move(map);
  builders_ = std::move(builders);
  for (auto& [id, b] : builders_) b.set_progress(progress_);
  region_of_scan_ = std::move(region_of_scan);
  scan_inputs_ = std::move(inputs);
  entered_utime_ = std::move(entered);
  scans_since_entering_ = since;
  dirty_ = std::move(dirty);
}

void RgKernel::restore(const std::string& snapshot_bytes)
{
  persist::ByteReader r(snapshot_bytes);
  restore_state(r);
}

}  // namespace rgnav::rg_kernel
