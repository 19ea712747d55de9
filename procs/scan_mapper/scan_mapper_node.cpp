#include "scan_mapper/scan_mapper_node.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "config/string_fields.h"
#include "rgnav/heartbeat_t.hpp"
#include "scan_mapper/scan_mapper_conversions.h"

namespace rgnav::scan_mapper {

ScanMapperChannels load_scan_mapper_channels(const config::Config& c)
{
  ScanMapperChannels ch;
  config::read_strings(c, {{"laser", &ch.laser}, {"odometry", &ch.odometry}, {"aligned_scan", &ch.aligned_scan},
                           {"slam_pose", &ch.slam_pose}, {"sensor", &ch.sensor}});
  return ch;
}

PersistenceOptions load_persistence_options(const config::Config& c)
{
  PersistenceOptions p;
  p.state_file = c.string("state_file", p.state_file);
  p.resume = c.boolean("resume", p.resume);
  p.snapshot_every_records = static_cast<int>(c.integer("snapshot_every_records", p.snapshot_every_records, 1, 100000));
  p.fsync_each_record = c.boolean("fsync_each_record", p.fsync_each_record);
  return p;
}

ScanMapperNode::ScanMapperNode(runtime::Node& node, const ScanMapperOptions& options, ScanMapperChannels channels,
                               PersistenceOptions persistence)
    : node_(node), channels_(std::move(channels))
{
  if (!persistence.state_file.empty()) {
    store_ = std::make_unique<MapperStore>(StoreOptions{persistence.state_file, persistence.resume,
                                                        persistence.snapshot_every_records, persistence.fsync_each_record});
    const RecoveryReport& r = store_->report();
    if (!r.damage.empty()) spdlog::error("persisted state {}: {}", persistence.state_file, r.damage);
    PersistedState st = store_->take_recovered();
    ids_ = ScanIdIssuer(st.ids);
    if (r.scans > 0) {
      // The fault harness reads "resuming from persisted state <file> (<N> scans".
      spdlog::info("resuming from persisted state {} ({} scans, {} edges; {} from the snapshot, {} journal records replayed); next scan id > {}",
                   persistence.state_file, r.scans, r.edges, r.snapshot_scans, r.records_replayed, st.ids.last_issued);
      mapper_ = std::make_unique<ScanMapper>(options, std::move(st.mapper));
    }
  }
  if (!mapper_) {
    spdlog::info("starting a new map at a fresh origin{}", store_ ? "" : " (persistence disabled)");
    mapper_ = std::make_unique<ScanMapper>(options);
  }
  mapper_->set_deferred_optimization(true);
  mapper_->set_progress([this] { node_.note_progress(); });
  node_.subscribe<odometry_t>(channels_.odometry, [this](const odometry_t& m) { on_odometry(to_odometry(m), m.seq); });
  node_.subscribe<laser_scan_t>(channels_.laser, [this](const laser_scan_t& m) { on_scan(msg::to_laser_scan(m)); });
  node_.watch_fd([this] { return worker_.fd(); }, [this] { on_optimization_done(); });
}

ScanMapperNode::~ScanMapperNode()
{
  // The job and the runner it uses are members: the worker must be done before they go. Its
  // result is dropped: the map without it is consistent and all that was published is stored.
  worker_.wait();
  try {
    if (store_) store_->snapshot(*mapper_, ids_.state());
  } catch (const std::exception& e) {
    spdlog::error("snapshot at exit failed (the journal still holds everything): {}", e.what());
  }
}

std::optional<RecoveryReport> ScanMapperNode::recovery() const
{
  if (!store_) return std::nullopt;
  return store_->report();
}

void ScanMapperNode::drop(const std::string& channel, const std::string& why) { node_.drops().drop(channel, why); }

void ScanMapperNode::on_odometry(const OdometrySample& sample, int64_t seq)
{
  if (const auto why = check_odometry(sample, limits_); !why.empty()) return drop(channels_.odometry, why);
  // A sequence that goes back means the base driver restarted with a new odometry origin.
  if (last_odometry_seq_ >= 0 && seq < last_odometry_seq_) {
    spdlog::warn("odometry sequence went back ({} -> {}): relocalising the next scan", last_odometry_seq_, seq);
    mapper_->reset_odometry();
    last_odometry_utime_ = -1;
    last_scan_utime_ = -1;  // a restarted source may restart its clock too
    odometry_jump_.reset();
  } else if (last_odometry_utime_ >= 0 && sample.utime < last_odometry_utime_) {
    last_odometry_seq_ = seq;
    return drop(channels_.odometry, "odometry time went back without a driver restart");
  } else if (last_odometry_utime_ >= 0 && sample.utime - last_odometry_utime_ > limits_.max_odometry_gap_us) {
    // Far ahead: a broken timestamp, or time really jumped. Believe it once a second sample
    // continues from it.
    const bool confirmed = odometry_jump_ && sample.utime >= odometry_jump_->utime &&
                           sample.utime - odometry_jump_->utime <= limits_.max_odometry_gap_us;
    if (!confirmed) {
      odometry_jump_ = sample;
      last_odometry_seq_ = seq;
      return drop(channels_.odometry, "odometry time jumped ahead (held until confirmed)");
    }
    spdlog::warn("odometry time jumped ahead by {} s: relocalising the next scan",
                 static_cast<double>(sample.utime - last_odometry_utime_) * 1e-6);
    mapper_->reset_odometry();
    mapper_->add_odometry(*odometry_jump_);
    last_scan_utime_ = -1;
  }
  odometry_jump_.reset();
  last_odometry_seq_ = seq;
  last_odometry_utime_ = sample.utime;
  mapper_->add_odometry(sample);
}

void ScanMapperNode::on_scan(const sensors::LaserScan& in)
{
  if (const auto why = check_scan(in, limits_); !why.empty()) return drop(channels_.laser, why);
  // Equal times are left to the gating (some logs stamp several scans alike); older is refused.
  if (in.utime < last_scan_utime_) return drop(channels_.laser, "scan older than the last accepted one");
  sensors::LaserScan scan = in;
  bool laser_restarted = false;
  scan.scan_id = ids_.id_for(in.scan_id, &laser_restarted);
  if (laser_restarted)
    spdlog::warn("laser scan ids went back (to {}): publishing them as {} on, so that ids never repeat", in.scan_id, scan.scan_id);
  const auto t0 = std::chrono::steady_clock::now();
  const MapperUpdate up = mapper_->add_scan(scan);
  const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (ms > 100.0) spdlog::debug("scan {} took {:.0f} ms on the node thread", scan.scan_id, ms);
  if (!up.accepted) return;
  last_scan_utime_ = scan.utime;
  ids_.issued(scan.scan_id);
  persist_and_publish(up, true);
  if (!up.matched) node_.set_status(heartbeat_t::STATE_DEGRADED, "scan matching failed; odometry only");
  else if (!persist_failed_) node_.clear_status();
  if (up.optimization_ready) start_optimization();
}

void ScanMapperNode::persist_and_publish(const MapperUpdate& up, bool new_scan)
{
  if (store_) {
    try {
      if (new_scan) store_->record_scan(*mapper_, up.node, ids_.state());
      if (up.loop_closed) store_->record_estimates(*mapper_, ids_.state());
      persist_failed_ = false;
    } catch (const std::exception& e) {
      // The robot is better served by a mapper that goes on than by one that stops; but a
      // restart would now lose what follows, and the supervisor should know.
      spdlog::error("journal write failed: {}", e.what());
      persist_failed_ = true;
      node_.set_status(heartbeat_t::STATE_DEGRADED, "journal write failed: a restart would lose scans");
    }
  }
  const auto& nodes = mapper_->nodes();
  const Pose2& mount = mapper_->options().base_from_laser;
  for (int i : up.corrected)
    node_.publish(channels_.aligned_scan, to_aligned_scan(nodes[static_cast<size_t>(i)], mount, channels_.sensor));
  const ScanNode& n = nodes[static_cast<size_t>(up.node)];
  if (new_scan) node_.publish(channels_.aligned_scan, to_aligned_scan(n, mount, channels_.sensor));
  if (const auto m_from_o = mapper_->map_from_odom()) node_.publish(channels_.slam_pose, to_slam_pose(n, *m_from_o));
  if (up.loop_closed)
    spdlog::info("loop closed at scan {}: {} earlier scans corrected", n.scan.scan_id, up.corrected.size());
}

void ScanMapperNode::start_optimization()
{
  job_ = mapper_->take_optimization_job();
  if (!job_) return;
  ++optimizations_started_;
  OptimizationJob* job = &*job_;
  worker_.start([this, job] {
    const auto t0 = std::chrono::steady_clock::now();
    runner_(*job);
    job_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  });
}

void ScanMapperNode::on_optimization_done()
{
  if (!worker_.finished()) return;
  if (!worker_.error().empty() || !job_) {
    spdlog::error("pose graph optimisation failed: {}", worker_.error());
    mapper_->cancel_optimization();
    job_.reset();
    return;
  }
  spdlog::debug("pose graph optimisation of {} nodes took {:.0f} ms on the worker", job_->graph.size(), job_ms_);
  const MapperUpdate up = mapper_->apply_optimization(*job_);
  job_.reset();
  ++optimizations_applied_;
  if (up.loop_closed) persist_and_publish(up, false);
}

}  // namespace rgnav::scan_mapper
