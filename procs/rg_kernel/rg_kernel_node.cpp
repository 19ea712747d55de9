#include "procs/rg_kernel/rg_kernel_node.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "config/string_fields.h"
#include "msg/conversions.h"
#include "persist/atomic_file.h"
#include "persist/byte_codec.h"
#include "procs/rg_kernel/rg_kernel_conversions.h"
#include "procs/rg_kernel/rg_kernel_options.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/saved_map.h"

namespace rgnav::rg_kernel {

NodeConfig load_node_config(const config::Config& cfg, const config::RobotDescription& robot, const std::string& repo_root)
{
  NodeConfig c;
  c.kernel = load_kernel_options(cfg, robot);
  c.graph = load_graph_options(cfg.section("graph"));
  const auto p = cfg.section("persistence");
  c.state_dir = p.string("state_dir", "logs/state/rg_kernel");
  if (!c.state_dir.empty() && c.state_dir[0] != '/') c.state_dir = repo_root + "/" + c.state_dir;
  c.sync_every_inputs = static_cast<int>(p.integer("sync_every_inputs", c.sync_every_inputs, 1, 100000));
  c.sync_period_s = p.number("sync_period_s", c.sync_period_s, 0.001, 10.0);
  c.snapshot_every_inputs = p.integer("snapshot_every_inputs", c.snapshot_every_inputs, 0, 10000000);
  c.export_period_s = p.number("export_period_s", c.export_period_s, 0.0, 3600.0);
  c.publish_period_s = cfg.section("publish").number("period_s", c.publish_period_s, 0.05, 60.0);
  const auto ch = cfg.section("channels");
  config::read_strings(ch, {{"aligned_scan", &c.aligned_scan}, {"gateway_events", &c.gateway_events},
                            {"rg_map", &c.rg_map}, {"rg_region", &c.rg_region}, {"rg_graph", &c.rg_graph},
                            {"region_name", &c.region_name}, {"objects3d", &c.objects3d}});
  return c;
}

RgKernelNode::RgKernelNode(runtime::Node& node, NodeConfig config)
    : node_(node), config_(std::move(config)), kernel_(config_.kernel)
{
  // Long work on the message thread (a journal replay, a gateway traversal, describing a loop
  // closure's regions again) counts its steps: the heartbeat goes on beside the loop, and the
  // supervisor's work bound sees progress instead of a hang.
  kernel_.set_progress([this] { node_.note_progress(); });
  if (!config_.state_dir.empty()) restore();
  node_.subscribe<aligned_scan_t>(config_.aligned_scan, [this](const aligned_scan_t& m) { on_scan(m, true); });
  node_.subscribe<gateway_event_t>(config_.gateway_events, [this](const gateway_event_t& m) { on_event(m, true); });
  if (!config_.region_name.empty())
    node_.subscribe<region_name_t>(config_.region_name, [this](const region_name_t& m) { on_region_name(m, true); });
  if (!config_.objects3d.empty())
    node_.subscribe<objects3d_t>(config_.objects3d, [this](const objects3d_t& m) { on_objects(m, true); });
  node_.every(std::chrono::seconds(1), [this] {
    if (kernel_.map().current_region != 0) publish();
  });
  if (store_) {
    node_.every(std::chrono::microseconds(static_cast<int64_t>(config_.sync_period_s * 1e6)), [this] {
      try {
        store_->sync_if_due();
      } catch (const std::exception& e) {
        spdlog::error("journal sync failed: {}", e.what());
        node_.set_status(heartbeat_t::STATE_DEGRADED, "journal sync failed");
      }
    });
  }
  if (restored_ > 0) publish();
}

namespace {
constexpr uint32_t kSnapshotMagic = 0x534b4752;   // "RGKS"
}

std::string RgKernelNode::snapshot_payload() const
{
  persist::ByteWriter w;
  w.put(kSnapshotMagic);
  w.put(inputs_);
  w.put(last_publish_utime_);
  w.put(static_cast<uint8_t>(unpublished_change_));
  kernel_.save_state(w);   // last: it runs to the end
  return w.take();
}

void RgKernelNode::apply_snapshot(const std::string& payload)
{
  persist::ByteReader r(payload);
  if (r.get<uint32_t>() != kSnapshotMagic) throw persist::CorruptBytes("not an rg_kernel snapshot");
  const int64_t inputs = r.get<int64_t>(), last_publish = r.get<int64_t>();
  const bool unpublished = r.get<uint8_t>() != 0;
  kernel_.restore_state(r);
  inputs_ = inputs;
  last_publish_utime_ = last_publish;
  unpublished_change_ = unpublished;
}

void RgKernelNode::restore()
{
  StoreOptions so;
  so.dir = config_.state_dir;
  so.sync_every_records = config_.sync_every_inputs;
  so.sync_every = std::chrono::milliseconds(static_cast<int64_t>(config_.sync_period_s * 1000));
  so.snapshot_every_records = config_.snapshot_every_inputs;
  store_ = std::make_unique<StateStore>(so);
  // The newest intact snapshot; a damaged one is reported and set aside, never loaded, and
  // the one before it (with the longer journal tail kept for exactly this) takes its place.
  const auto t0 = std::chrono::steady_clock::now();
  for (const int64_t g : store_->snapshot_generations()) {
    try {
      apply_snapshot(store_->read_snapshot(g));
      loaded_generation_ = g;
      break;
    } catch (const std::exception& e) {   // persist::CorruptFile, persist::CorruptBytes
      spdlog::error("snapshot {} is damaged and will not be loaded: {}", store_->snapshot_path(g), e.what());
      store_->set_aside(g, store_->snapshot_path(g) + ": " + e.what());
    }
  }
  const int64_t from_snapshot = inputs_;
  const auto t1 = std::chrono::steady_clock::now();
  // Replay what was journaled after it: same inputs, same order, same map. A long tail (after
  // a fallback) takes a while.
  replaying_ = true;
  for (const auto& rec : store_->open_from(loaded_generation_)) {
    node_.note_progress();
    std::string why;
    const auto* data = reinterpret_cast<const uint8_t*>(rec.bytes.data());
    if (rec.tag == kAlignedScan) {
      aligned_scan_t m;
      if (bus::decode(data, rec.bytes.size(), &m, &why)) on_scan(m, false);
    } else if (rec.tag == kGatewayEvent) {
      gateway_event_t m;
      if (bus::decode(data, rec.bytes.size(), &m, &why)) on_event(m, false);
    } else if (rec.tag == kRegionName) {
      region_name_t m;
      if (bus::decode(data, rec.bytes.size(), &m, &why)) on_region_name(m, false);
    } else if (rec.tag == kObjects3dInMap) {
      objects3d_t m;
      if (bus::decode(data, rec.bytes.size(), &m, &why)) on_objects(m, false);
    }
    if (!why.empty()) spdlog::warn("journal record skipped: {}", why);
    ++inputs_;
    ++replayed_;
  }
  replaying_ = false;
  restored_ = inputs_;
  if (!store_->tail_damage().empty()) spdlog::warn("journal {}", store_->tail_damage());
  for (const auto& p : store_->problems()) spdlog::error("state {}: {}", config_.state_dir, p);
  if (!store_->problems().empty())
    node_.set_status(heartbeat_t::STATE_DEGRADED, "state damaged, restored from what was intact: " + store_->problems().front());
  const auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
  if (restored_ > 0)
    spdlog::info("resumed from {}: {} inputs replayed ({} from snapshot generation {} in {:.0f} ms, {} from the journal in {:.0f} ms), "
                 "{} regions",
                 config_.state_dir, restored_, from_snapshot, loaded_generation_, ms(t1 - t0), replayed_,
                 ms(std::chrono::steady_clock::now() - t1), kernel_.stats().regions);
  else
    spdlog::info("starting a fresh map in {} (0 inputs, 0 regions)", config_.state_dir);
}

void RgKernelNode::maybe_snapshot()
{
  if (!store_ || !store_->snapshot_due()) return;
  const std::string error = store_->last_snapshot_error();
  if (!error.empty()) {
    // The previous attempt failed; the journal chain since the last good snapshot is intact.
    spdlog::error("snapshot failed: {}", error);
    node_.set_status(heartbeat_t::STATE_DEGRADED, "snapshot failed");
  }
  try {
    store_->start_snapshot(snapshot_payload());
  } catch (const std::exception& e) {
    spdlog::error("snapshot failed: {}", e.what());
    node_.set_status(heartbeat_t::STATE_DEGRADED, "snapshot failed");
  }
}

void RgKernelNode::snapshot_now()
{
  if (!store_) return;
  store_->wait_snapshot();
  store_->start_snapshot(snapshot_payload());
  store_->wait_snapshot();
}

template <class T>
void RgKernelNode::journal(Tag tag, const T& m)
{
  if (!store_) return;
  std::vector<uint8_t> buf;
  std::string why;
  if (!bus::encode(m, &buf, &why)) return;
  store_->append(tag, std::string(buf.begin(), buf.end()));
  ++inputs_;
}

void RgKernelNode::on_scan(const aligned_scan_t& m, bool write_journal)
{
  if (write_journal) journal(kAlignedScan, m);
  map_from_odom_[m.scan_id] = msg::to_pose2(m.map_from_base) * msg::to_pose2(m.odom_from_base).inverse();
  constexpr size_t kKeptScans = 2000;  // minutes of scans: objects arrive within a frame or two
  while (map_from_odom_.size() > kKeptScans) map_from_odom_.erase(map_from_odom_.begin());
  if (kernel_.add_scan(to_input(m))) changed(m.utime);
  if (write_journal) maybe_snapshot();
}

void RgKernelNode::on_objects(objects3d_t m, bool write_journal)
{
  if (write_journal) {
    // Re-anchor by scan id (diss. 3.3.5): the correction of the scan taken at capture, else (the
    // mapper keeps only some scans) the newest one; without any scan yet there is no map to put
    // them in. Journaled in the map frame: the corrections are live state a replay lacks.
    if (map_from_odom_.empty()) return node_.drops().drop(config_.objects3d, "no aligned scan yet to anchor objects to");
    const auto it = map_from_odom_.find(m.scan_id);
    const geometry::Pose2 map_from_odom = it != map_from_odom_.end() ? it->second : map_from_odom_.rbegin()->second;
    m.odom_from_base = msg::to_msg(map_from_odom * msg::to_pose2(m.odom_from_base));
  }
  std::string why;
  const auto rects = to_rectangles(m, msg::to_pose2(m.odom_from_base), &why);
  if (!why.empty()) return node_.drops().drop(config_.objects3d, why);
  if (rects.empty()) return;
  if (write_journal) journal(kObjects3dInMap, m);
  if (kernel_.add_objects3d(m.utime, rects)) changed(m.utime);
  if (write_journal) maybe_snapshot();
}

void RgKernelNode::on_event(const gateway_event_t& m, bool write_journal)
{
  if (write_journal) journal(kGatewayEvent, m);
  if (kernel_.add_gateway_event(to_input(m))) changed(m.utime);
  if (write_journal) maybe_snapshot();
}

void RgKernelNode::on_region_name(const region_name_t& m, bool write_journal)
{
  std::string why;
  if (write_journal) {
    // Checked before it is journaled: a refused name leaves no trace in the state, and a name
    // said again changes nothing and is not journaled twice.
    const int64_t id = rgmap::region_to_name(kernel_.map(), m.region_id, m.name, &why);
    if (id == 0) return node_.drops().drop(config_.region_name, "region name refused: " + why);
    if (kernel_.map().region(id)->name == m.name) return;
    journal(kRegionName, m);
  }
  if (!kernel_.name_region(m.region_id, m.name, &why)) {
    if (!why.empty()) spdlog::warn("journaled region name not applied: {}", why);
    return;
  }
  unpublished_change_ = true;
  // Published at once, not on the scan schedule: the operator waits for it, and its wall-time
  // stamp must not move the schedule of message time.
  if (!replaying_) publish();
  if (write_journal) maybe_snapshot();
}

void RgKernelNode::changed(int64_t utime)
{
  unpublished_change_ = true;
  if (utime - last_publish_utime_ >= static_cast<int64_t>(config_.publish_period_s * 1e6)) {
    last_publish_utime_ = utime;
    // While replaying, the schedule advances as it did but nothing goes out (old versions of
    // the map, each with an fsync'ed checkpoint): the restored map is published once at the end.
    if (!replaying_) publish();
  }
}

void RgKernelNode::publish()
{
  // After a loop closure every corrected region is described again (line map, freespace,
  // objects): seconds for a large map on a busy machine. Each region counts as progress, else
  // the supervisor takes the kernel for hung and restarts it (seen in the demo after a closure
  // that corrected 1135 scans).
  const auto start = std::chrono::steady_clock::now();
  const size_t stale = kernel_.stale_regions();
  const rgmap::RgMap& map = kernel_.refreshed_map([this] { node_.note_progress(); });
  const double refresh_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (refresh_ms > 200.0) spdlog::info("{} region(s) described again in {:.0f} ms", stale, refresh_ms);
  if (map.current_region == 0) return;
  // Publish only what is durable: a map out on the bus is an acknowledgement of its inputs.
  if (store_) {
    try {
      store_->sync();
    } catch (const std::exception& e) {
      spdlog::error("journal sync failed, not publishing: {}", e.what());
      node_.set_status(heartbeat_t::STATE_DEGRADED, "journal sync failed");
      return;
    }
  }
  rg_map_t map_msg = rgmap::to_msg(map);
  node_.publish(config_.rg_region, rgmap::to_msg(*map.region(map.current_region)));
  node_.publish(config_.rg_map, map_msg);
  node_.publish(config_.rg_graph, rgmap::to_msg(rgmap::build_graph(map, config_.graph), map.utime));
  if (unpublished_change_ && !config_.state_dir.empty()) export_pending_ = true;
  unpublished_change_ = false;
  // rgmap.json is an export for tools (render, map); restarts use snapshots and the journal.
  // Under a flood of input it is written at most every export_period (wall time).
  const auto now = std::chrono::steady_clock::now();
  if (export_pending_ && now - last_export_ >= std::chrono::duration<double>(config_.export_period_s)) write_export(map);
}

void RgKernelNode::write_export(const rgmap::RgMap& map)
{
  try {
    rgmap::save_map(map, config_.state_dir + "/rgmap.json");
    export_pending_ = false;
    last_export_ = std::chrono::steady_clock::now();
  } catch (const std::exception& e) {
    spdlog::error("rgmap.json export failed: {}", e.what());
    node_.set_status(heartbeat_t::STATE_DEGRADED, "rgmap.json export failed");
  }
}

RgKernelNode::~RgKernelNode()
{
  // A clean stop leaves the newest map in rgmap.json (a kill leaves the one before: the
  // snapshots and the journal hold the rest).
  if (export_pending_ && kernel_.map().current_region != 0) write_export(kernel_.refreshed_map());
}

}  // namespace rgnav::rg_kernel
