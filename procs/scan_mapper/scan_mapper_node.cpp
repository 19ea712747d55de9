#include "scan_mapper/scan_mapper_node.h"

#include <spdlog/spdlog.h>

#include "rgnav/heartbeat_t.hpp"
#include "scan_mapper/mapper_state_io.h"
#include "scan_mapper/scan_mapper_conversions.h"

namespace rgnav::scan_mapper {

ScanMapperChannels load_scan_mapper_channels(const config::Config& c)
{
  ScanMapperChannels ch;
  ch.laser = c.string("laser", ch.laser);
  ch.odometry = c.string("odometry", ch.odometry);
  ch.aligned_scan = c.string("aligned_scan", ch.aligned_scan);
  ch.slam_pose = c.string("slam_pose", ch.slam_pose);
  ch.sensor = c.string("sensor", ch.sensor);
  return ch;
}

PersistenceOptions load_persistence_options(const config::Config& c)
{
  PersistenceOptions p;
  p.state_file = c.string("state_file", p.state_file);
  p.resume = c.boolean("resume", p.resume);
  p.save_every_scans = static_cast<int>(c.integer("save_every_scans", p.save_every_scans, 1, 100000));
  return p;
}

ScanMapperNode::ScanMapperNode(runtime::Node& node, const ScanMapperOptions& options, ScanMapperChannels channels,
                               PersistenceOptions persistence)
    : node_(node), channels_(std::move(channels)), persistence_(std::move(persistence))
{
  std::optional<MapperState> state;
  if (!persistence_.state_file.empty() && persistence_.resume) {
    try {
      state = load_state(persistence_.state_file);
    } catch (const std::exception& e) {
      // A damaged file is kept for inspection and never half-loaded.
      spdlog::error("not resuming: {}", e.what());
    }
  }
  if (state) {
    spdlog::info("resuming from persisted state {} ({} scans, {} edges)", persistence_.state_file, state->nodes.size(),
                 state->edges.size());
    mapper_ = std::make_unique<ScanMapper>(options, std::move(*state));
  } else {
    spdlog::info("starting a new map at a fresh origin{}",
                 persistence_.state_file.empty() ? " (persistence disabled)" : "");
    mapper_ = std::make_unique<ScanMapper>(options);
  }
  node_.subscribe<odometry_t>(channels_.odometry, [this](const odometry_t& m) { on_odometry(to_odometry(m), m.seq); });
  node_.subscribe<laser_scan_t>(channels_.laser, [this](const laser_scan_t& m) { on_scan(to_scan(m)); });
}

ScanMapperNode::~ScanMapperNode()
{
  try {
    if (unsaved_ > 0) save();
  } catch (const std::exception& e) {
    spdlog::error("saving state at exit failed: {}", e.what());
  }
}

void ScanMapperNode::save()
{
  if (persistence_.state_file.empty()) return;
  save_state(mapper_->state(), persistence_.state_file);
  unsaved_ = 0;
}

void ScanMapperNode::on_odometry(const OdometrySample& sample, int64_t seq)
{
  // A sequence that goes back means the base driver restarted with a new odometry origin.
  if (last_odometry_seq_ >= 0 && seq < last_odometry_seq_) {
    spdlog::warn("odometry sequence went back ({} -> {}): relocalising the next scan", last_odometry_seq_, seq);
    mapper_->reset_odometry();
  }
  last_odometry_seq_ = seq;
  mapper_->add_odometry(sample);
}

void ScanMapperNode::on_scan(const Scan& scan)
{
  const MapperUpdate up = mapper_->add_scan(scan);
  if (!up.accepted) return;
  const auto& nodes = mapper_->nodes();
  const Pose2& mount = mapper_->options().base_from_laser;
  for (int i : up.corrected)
    node_.publish(channels_.aligned_scan, to_aligned_scan(nodes[static_cast<size_t>(i)], mount, channels_.sensor));
  const ScanNode& n = nodes[static_cast<size_t>(up.node)];
  node_.publish(channels_.aligned_scan, to_aligned_scan(n, mount, channels_.sensor));
  if (const auto m_from_o = mapper_->map_from_odom()) node_.publish(channels_.slam_pose, to_slam_pose(n, *m_from_o));
  if (up.loop_closed)
    spdlog::info("loop closed at scan {}: {} earlier scans corrected", n.scan.scan_id, up.corrected.size());
  if (!up.matched) node_.set_status(heartbeat_t::STATE_DEGRADED, "scan matching failed; odometry only");
  else node_.clear_status();
  if (++unsaved_ >= persistence_.save_every_scans || up.loop_closed) {
    try {
      save();
    } catch (const std::exception& e) {
      spdlog::error("saving state failed: {}", e.what());
    }
  }
}

}  // namespace rgnav::scan_mapper
