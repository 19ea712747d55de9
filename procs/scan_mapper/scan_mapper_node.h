// Node adapter of the scan mapper: ODOMETRY and LASER_FRONT in, ALIGNED_SCAN (new scans and,
// after a loop closure, corrected earlier scans with revision + 1) and SLAM_POSE out.
//
// Inputs are checked at the boundary (input_checks.h, plus time and sequence order): a bad
// one is dropped and counted (Node::drops) and never reaches the map or its persisted state.
// Every accepted scan and every correction is journaled durably before it is published
// (mapper_store.h), so a restart resumes with every published scan; scan ids continue
// (scan_ids.h). The pose graph optimisation after a loop closure runs on a worker thread
// (background_job.h) so that the node keeps taking scans and heartbeating meanwhile; its
// result is adopted on the node thread.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "config/config.h"
#include "runtime/node.h"
#include "scan_mapper/background_job.h"
#include "scan_mapper/input_checks.h"
#include "scan_mapper/mapper_store.h"
#include "scan_mapper/scan_ids.h"
#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

struct ScanMapperChannels
{
  std::string laser = "LASER_FRONT";
  std::string odometry = "ODOMETRY";
  std::string aligned_scan = "ALIGNED_SCAN";
  std::string slam_pose = "SLAM_POSE";
  std::string sensor = "laser_front";  // sensor name in republished scans
};
ScanMapperChannels load_scan_mapper_channels(const config::Config& section);

struct PersistenceOptions
{
  std::string state_file;           // snapshot; the journal is state_file + ".journal"; "" = none
  bool resume = true;               // load what is stored at start
  int snapshot_every_records = 100; // journal records between snapshots
  bool fsync_each_record = true;    // durable before publishing (off only for tests)
};
PersistenceOptions load_persistence_options(const config::Config& section);

class ScanMapperNode
{
 public:
  ScanMapperNode(runtime::Node& node, const ScanMapperOptions& options, ScanMapperChannels channels,
                 PersistenceOptions persistence);
  // A clean stop: waits for a running optimisation, writes a snapshot.
  ~ScanMapperNode();

  const ScanMapper& mapper() const { return *mapper_; }
  // What the start recovered (nullopt without persistence).
  std::optional<RecoveryReport> recovery() const;
  const ScanIdState& scan_ids() const { return ids_.state(); }
  int64_t optimizations_started() const { return optimizations_started_; }
  int64_t optimizations_applied() const { return optimizations_applied_; }
  bool optimization_running() const { return worker_.busy(); }

  // Tests: runs each optimisation job on the worker (default: job.run()).
  void set_optimization_runner(std::function<void(OptimizationJob&)> runner) { runner_ = std::move(runner); }

 private:
  void on_odometry(const OdometrySample& sample, int64_t seq);
  void on_scan(const sensors::LaserScan& scan);
  void on_optimization_done();
  void drop(const std::string& channel, const std::string& why);
  // Journals (if persistent), then publishes the given corrections, the node and SLAM_POSE.
  void persist_and_publish(const MapperUpdate& up, bool new_scan);
  void start_optimization();

  runtime::Node& node_;
  ScanMapperChannels channels_;
  InputLimits limits_;
  std::unique_ptr<MapperStore> store_;
  std::unique_ptr<ScanMapper> mapper_;
  ScanIdIssuer ids_;
  int64_t last_odometry_seq_ = -1;
  int64_t last_odometry_utime_ = -1;
  std::optional<OdometrySample> odometry_jump_;  // a sample far ahead in time, not yet confirmed
  int64_t last_scan_utime_ = -1;   // newest accepted scan of this process
  bool persist_failed_ = false;
  BackgroundJob worker_;
  std::optional<OptimizationJob> job_;  // owned by the worker while it runs
  double job_ms_ = 0.0;                 // written by the worker, read after it finished
  std::function<void(OptimizationJob&)> runner_ = [](OptimizationJob& j) { j.run(); };
  int64_t optimizations_started_ = 0, optimizations_applied_ = 0;
};

}  // namespace rgnav::scan_mapper
