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

// CPU time this thread has used [s] (mapping costs are timed per thread).
double thread_cpu_seconds();

OfflineResult run_offline(const importers::ImportedLog& log, const ScanMapperOptions& options);

// trajectory.txt (scan_id utime x y theta for every accepted scan), aligned_scans.lcmlog
// (ALIGNED_SCAN of the final estimates), map.png; returns the consistency of that map.
double write_outputs(const OfflineResult& result, const ScanMapperOptions& options, const std::string& dir);

// truth_pairs.txt of the simulated benches: per accepted scan, scan_id utime, the true pose
// (truth[k] for nodes[k]) and the final estimate; with `online` also each node's estimate when
// it was added and whether its scan closed a loop (loop_closed_at: node indices, ascending).
// deploy/tools/truth_pairs_errors.py reads it.
void write_truth_pairs(const std::string& path, const std::vector<ScanNode>& nodes, const std::vector<Pose2>& truth,
                       const std::vector<Pose2>* online = nullptr, const std::vector<int>* loop_closed_at = nullptr);

}  // namespace rgnav::scan_mapper
