// The RG mapping pipeline over a whole recorded log, and what `./rgnav map` writes from it.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "importers/log_records.h"
#include "offline_mapping.h"
#include "rgmap_metrics.h"
#include "rgmap_pipeline.h"

namespace rgnav::rgmap_pipeline {

struct OfflineRun
{
  std::vector<scan_mapper::ScanNode> nodes;   // accepted scans, final estimates
  scan_mapper::MapperStats mapper_stats;
  PipelineCounts counts;
  rgmap::RgMap map;                            // every region described from all its scans
  rg_kernel::KernelStats kernel_stats;
  rg_kernel::LineMapFidelity fidelity;         // raw scan points against their regions' line maps
  std::map<int64_t, std::vector<Eigen::Vector2d>> robot_positions;   // live region -> its scans' laser positions (map frame)
  double cpu_seconds = 0;                      // this thread, whole pipeline
  double log_seconds = 0;                      // message time from the first to the last scan
};

using scan_mapper::thread_cpu_seconds;

// Feeds the log's scans and odometry in file order (odometry first where a log interleaves them
// by time, as the bus would deliver them).
OfflineRun run_pipeline(const importers::ImportedLog& log, const LoadedPipeline& loaded);
OfflineRun finish_run(const RgMapPipeline& pipeline);

struct OutputOptions
{
  double pixels_per_metre = 40;   // RG map pictures
  double export_resolution = 0.05;  // [m] map_server export
  bool pictures = true;           // rgmap.svg / rgmap.png / the export (tests may skip them)
};

// DIR/trajectory.txt, aligned_scans.lcmlog, map.png (as rgnav_map writes them), rgmap.json
// (rgnav persist framing, as the RG kernel checkpoints it: ./rgnav render reads it),
// rgmap.svg, rgmap.png, rgmap_global.pgm + rgmap_global.yaml, summary.json (counts).
// Returns the summary written.
nlohmann::json write_run_outputs(const OfflineRun& run, const PipelineOptions& options, const std::string& dir,
                                 const OutputOptions& out = {});

nlohmann::json summary_json(const OfflineRun& run);
nlohmann::json counts_json(const MapCounts& c);
// points_explained (share of raw scan points within fidelity.tolerance of a segment of their
// region's line map) and point_map_distance_m (their mean distance, each capped at fidelity.cap).
void add_fidelity_json(const rg_kernel::LineMapFidelity& f, nlohmann::json* j);

}  // namespace rgnav::rgmap_pipeline
