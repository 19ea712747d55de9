// Runs the mapping library over a whole recorded log, deterministically and as fast as the CPU
// allows, and writes what the `rgnav map` tool and the SLAM benchmark produce.
#pragma once

#include <string>
#include <vector>

#include "importers/log_records.h"
#include "scan_mapper/occupancy_map.h"
#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

struct ScanEstimate
{
  int64_t scan_id = 0, utime = 0;
  Pose2 odom_from_base;
  Pose2 map_from_base;  // accepted: final estimate; others: registered between them (run_offline)
};

struct OfflineResult
{
  std::vector<ScanNode> nodes;
  std::vector<ScanEstimate> scans;  // every scan that had odometry
  MapperStats stats;
  double cpu_seconds = 0.0;         // CPU time of the mapping (this thread)
  double wall_seconds = 0.0;
  double log_seconds = 0.0;         // message time from the first to the last scan
};

OfflineResult run_offline(const importers::ImportedLog& log, const ScanMapperOptions& options);

// trajectory.txt (scan_id utime x y theta for every accepted scan), aligned_scans.lcmlog
// (ALIGNED_SCAN of the final estimates), map.png; returns the consistency of that map.
double write_outputs(const OfflineResult& result, const ScanMapperOptions& options, const std::string& dir);

}  // namespace rgnav::scan_mapper
