#include "procs/rg_kernel/rg_kernel_node.h"

#include <spdlog/spdlog.h>

#include "persist/atomic_file.h"
#include "procs/rg_kernel/rg_kernel_conversions.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/rgmap_json.h"

namespace rgnav::rg_kernel {

NodeConfig load_node_config(const config::Config& cfg, const std::string& repo_root)
{
  NodeConfig c;
  const auto k = cfg.section("kernel");
  c.kernel.gateway_match_distance = k.number("gateway_match_distance_m", c.kernel.gateway_match_distance, 0.1, 5.0);
  c.kernel.merge_min_scans = static_cast<int>(k.integer("merge_min_scans", c.kernel.merge_min_scans, 1, 1000));
  c.kernel.merge_inside_ratio = k.number("merge_inside_ratio", c.kernel.merge_inside_ratio, 0.1, 1.0);
  const auto lines = cfg.section("line_map");
  c.kernel.build.merge.alpha_max = lines.number("merge_alpha_max_deg", 3.0, 0.1, 45.0) * M_PI / 180.0;
  c.kernel.build.merge.dl_max = lines.number("merge_dl_max_m", 0.020, 0.001, 1.0);
  c.kernel.build.merge.gap_max = lines.number("merge_gap_max_m", 0.150, 0.0, 5.0);
  c.kernel.build.extract.split_distance = lines.number("split_distance_m", c.kernel.build.extract.split_distance, 0.001, 1.0);
  c.kernel.build.extract.max_point_gap = lines.number("max_point_gap_m", c.kernel.build.extract.max_point_gap, 0.01, 5.0);
  c.kernel.build.extract.min_points = static_cast<int>(lines.integer("min_points", c.kernel.build.extract.min_points, 2, 1000));
  c.kernel.build.extract.min_length = lines.number("min_length_m", c.kernel.build.extract.min_length, 0.0, 10.0);
  const auto fs = cfg.section("freespace");
  c.kernel.build.freespace_resolution = fs.number("resolution_m", c.kernel.build.freespace_resolution, 0.02, 1.0);
  c.kernel.build.freespace_max_range = fs.number("max_range_m", c.kernel.build.freespace_max_range, 1.0, 80.0);
  const auto g = cfg.section("graph");
  c.graph.nominal_speed = g.number("nominal_speed_mps", c.graph.nominal_speed, 0.05, 3.0);
  c.graph.gateway_crossing_time = g.number("gateway_crossing_time_s", c.graph.gateway_crossing_time, 0.0, 600.0);
  const auto p = cfg.section("persistence");
  c.state_dir = p.string("state_dir", "logs/state/rg_kernel");
  if (!c.state_dir.empty() && c.state_dir[0] != '/') c.state_dir = repo_root + "/" + c.state_dir;
  c.fsync_each_input = p.boolean("fsync_each_input", c.fsync_each_input);
  c.publish_period_s = cfg.section("publish").number("period_s", c.publish_period_s, 0.05, 60.0);
  const auto ch = cfg.section("channels");
  c.aligned_scan = ch.string("aligned_scan", c.aligned_scan);
  c.gateway_events = ch.string("gateway_events", c.gateway_events);
  c.rg_map = ch.string("rg_map", c.rg_map);
  c.rg_region = ch.string("rg_region", c.rg_region);
  c.rg_graph = ch.string("rg_graph", c.rg_graph);
  return c;
}

RgKernelNode::RgKernelNode(runtime::Node& node, NodeConfig config)
    : node_(node), config_(std::move(config)), kernel_(config_.kernel)
{
  if (!config_.state_dir.empty()) {
    journal_ = std::make_unique<persist::Journal>(config_.state_dir + "/inputs.journal", config_.fsync_each_input);
    if (!journal_->damage().empty())
      spdlog::warn("journal {}: {} — the damaged tail was cut off", config_.state_dir, journal_->damage());
    // Replay what was acknowledged before the last stop: same inputs, same order, same map.
    // A long journal takes a while: keep heartbeating so the supervisor sees progress.
    auto last_beat = std::chrono::steady_clock::now();
    for (const auto& rec : journal_->recovered()) {
      if (std::chrono::steady_clock::now() - last_beat > std::chrono::milliseconds(200)) {
        node_.publish_heartbeat();
        last_beat = std::chrono::steady_clock::now();
      }
      std::string why;
      const auto* data = reinterpret_cast<const uint8_t*>(rec.bytes.data());
      if (rec.tag == kAlignedScan) {
        aligned_scan_t m;
        if (bus::decode(data, rec.bytes.size(), &m, &why)) on_scan(m, false);
      } else if (rec.tag == kGatewayEvent) {
        gateway_event_t m;
        if (bus::decode(data, rec.bytes.size(), &m, &why)) on_event(m, false);
      }
      if (!why.empty()) spdlog::warn("journal record skipped: {}", why);
      ++restored_;
    }
    spdlog::info(restored_ > 0 ? "resumed from {}: {} inputs replayed, {} regions"
                               : "starting a fresh map in {} ({} inputs, {} regions)",
                 config_.state_dir, restored_, kernel_.stats().regions);
  }
  node_.subscribe<aligned_scan_t>(config_.aligned_scan, [this](const aligned_scan_t& m) { on_scan(m, true); });
  node_.subscribe<gateway_event_t>(config_.gateway_events, [this](const gateway_event_t& m) { on_event(m, true); });
  node_.every(std::chrono::seconds(1), [this] {
    if (kernel_.map().current_region != 0) publish();
  });
  if (restored_ > 0) publish();
}

template <class T>
void RgKernelNode::journal(Tag tag, const T& m)
{
  if (!journal_) return;
  std::vector<uint8_t> buf;
  std::string why;
  if (!bus::encode(m, &buf, &why)) return;
  journal_->append(tag, std::string(buf.begin(), buf.end()));
}

void RgKernelNode::on_scan(const aligned_scan_t& m, bool write_journal)
{
  if (write_journal) journal(kAlignedScan, m);
  if (kernel_.add_scan(to_input(m))) changed(m.utime);
}

void RgKernelNode::on_event(const gateway_event_t& m, bool write_journal)
{
  if (write_journal) journal(kGatewayEvent, m);
  if (kernel_.add_gateway_event(to_input(m))) changed(m.utime);
}

void RgKernelNode::changed(int64_t utime)
{
  unpublished_change_ = true;
  if (utime - last_publish_utime_ >= static_cast<int64_t>(config_.publish_period_s * 1e6)) {
    last_publish_utime_ = utime;
    publish();
  }
}

void RgKernelNode::publish()
{
  const rgmap::RgMap& map = kernel_.refreshed_map();
  if (map.current_region == 0) return;
  rg_map_t map_msg = rgmap::to_msg(map);
  node_.publish(config_.rg_region, rgmap::to_msg(*map.region(map.current_region)));
  node_.publish(config_.rg_map, map_msg);
  node_.publish(config_.rg_graph, rgmap::to_msg(rgmap::build_graph(map, config_.graph), map.utime));
  if (unpublished_change_ && !config_.state_dir.empty()) {
    try {
      persist::write_atomically(config_.state_dir + "/rgmap.json", rgmap::to_json(map).dump(1));
    } catch (const std::exception& e) {
      spdlog::error("checkpoint failed: {}", e.what());
      node_.set_status(heartbeat_t::STATE_DEGRADED, "checkpoint failed");
    }
  }
  unpublished_change_ = false;
}

}  // namespace rgnav::rg_kernel
