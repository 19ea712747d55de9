// Node adapter of the scan mapper: ODOMETRY and LASER_FRONT in, ALIGNED_SCAN (new scans and,
// after a loop closure, corrected earlier scans with revision + 1) and SLAM_POSE out. Persists
// the mapper state atomically and resumes from it after a restart.
#pragma once

#include <memory>
#include <string>

#include "config/config.h"
#include "runtime/node.h"
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
  std::string state_file;      // "" = no persistence
  bool resume = true;          // load state_file at start when it exists
  int save_every_scans = 10;   // accepted scans between saves (also saved after each loop closure)
};
PersistenceOptions load_persistence_options(const config::Config& section);

class ScanMapperNode
{
 public:
  ScanMapperNode(runtime::Node& node, const ScanMapperOptions& options, ScanMapperChannels channels,
                 PersistenceOptions persistence);
  ~ScanMapperNode();

  const ScanMapper& mapper() const { return *mapper_; }
  // Writes the state now (also done periodically and at destruction).
  void save();

 private:
  void on_odometry(const OdometrySample& sample, int64_t seq);
  void on_scan(const Scan& scan);

  runtime::Node& node_;
  ScanMapperChannels channels_;
  PersistenceOptions persistence_;
  std::unique_ptr<ScanMapper> mapper_;
  int64_t last_odometry_seq_ = -1;
  int unsaved_ = 0;
};

}  // namespace rgnav::scan_mapper
