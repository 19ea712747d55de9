#include "offline_run.h"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "offline_mapping.h"
#include "rgmap/saved_map.h"
#include "render/rgmap_picture.h"

namespace rgnav::rgmap_pipeline {

OfflineRun finish_run(const RgMapPipeline& p)
{
  OfflineRun r;
  r.nodes = p.nodes();
  r.mapper_stats = p.mapper_stats();
  r.counts = p.counts();
  r.map = p.kernel().described_map();
  r.kernel_stats = p.kernel().stats();
  r.fidelity = p.kernel().line_map_fidelity();
  for (const auto& [id, region] : r.map.regions())
    if (region.state != rgmap::Region::State::kMerged) r.robot_positions[id] = p.kernel().robot_positions(id);
  return r;
}

OfflineRun run_pipeline(const importers::ImportedLog& log, const LoadedPipeline& loaded)
{
  const double cpu0 = thread_cpu_seconds();
  RgMapPipeline pipeline(loaded.options, loaded.classifier);
  int64_t next_id = 0;
  for (const auto& e : log.events) {
    if (e.kind == importers::LogEvent::Kind::kOdometry) {
      const auto& p = log.odometry[e.index];
      pipeline.add_odometry({p.utime, geometry::Pose2(p.x, p.y, p.theta)});
    } else if (e.kind == importers::LogEvent::Kind::kScan) {
      const auto& s = log.scans[e.index];
      sensors::LaserScan scan = s;
      scan.scan_id = s.scan_id > 0 ? s.scan_id : next_id + 1;   // logs without ids: count them
      next_id = std::max(next_id + 1, scan.scan_id);
      pipeline.add_scan(scan);
    }
  }
  OfflineRun r = finish_run(pipeline);
  r.cpu_seconds = thread_cpu_seconds() - cpu0;
  if (!log.scans.empty()) r.log_seconds = 1e-6 * static_cast<double>(log.scans.back().utime - log.scans.front().utime);
  return r;
}

nlohmann::json counts_json(const MapCounts& c)
{
  return {{"regions", c.regions},
          {"merged_regions", c.merged},
          {"gateways", c.gateways},
          {"doors", c.doors},
          {"neutralized", c.neutralized},
          {"not_traversed", c.not_traversed},
          {"segments", c.segments},
          {"scan_points", c.scan_points},
          {"compression", c.compression},
          {"mean_region_bytes", c.mean_region_bytes},
          {"mean_region_area_m2", c.mean_region_area_m2},
          {"consistency_problems", c.consistency_problems},
          {"overlapping_regions", c.overlapping_regions}};
}

void add_fidelity_json(const rg_kernel::LineMapFidelity& f, nlohmann::json* j)
{
  (*j)["points_explained"] = f.explained_share();
  (*j)["point_map_distance_m"] = f.mean_distance();
}

nlohmann::json summary_json(const OfflineRun& r)
{
  const auto& s = r.mapper_stats;
  nlohmann::json j = counts_json(count_map(r.map, r.kernel_stats.raw_points));
  add_fidelity_json(r.fidelity, &j);
  j["scans"] = s.scans_in;
  j["accepted_scans"] = s.accepted;
  j["loop_closures"] = s.loop_closures;
  j["corrections"] = r.counts.corrections;
  j["gateway_events"] = r.counts.events;
  j["gateway_traversals"] = r.counts.traversals;
  j["cpu_seconds"] = r.cpu_seconds;
  j["log_seconds"] = r.log_seconds;
  // null when the log's time stamps do not tell its duration (belgioioso's are truncated)
  j["realtime_factor"] = r.cpu_seconds > 0 && r.log_seconds > 0 ? nlohmann::json(r.log_seconds / r.cpu_seconds) : nlohmann::json();
  return j;
}

nlohmann::json write_run_outputs(const OfflineRun& r, const PipelineOptions& options, const std::string& dir,
                                 const OutputOptions& out)
{
  std::filesystem::create_directories(dir);
  // What rgnav_map writes, by the same code.
  scan_mapper::OfflineResult sm;
  sm.nodes = r.nodes;
  sm.stats = r.mapper_stats;
  scan_mapper::write_outputs(sm, options.mapper, dir);

  rgmap::save_map(r.map, dir + "/rgmap.json");
  if (out.pictures) {
    render::render_rgmap(r.map, dir + "/rgmap.svg", out.pixels_per_metre);
    render::render_rgmap(r.map, dir + "/rgmap.png", out.pixels_per_metre);
    render::write_map_server(render::compose_global_grid(r.map, out.export_resolution), dir + "/rgmap_global");
  }
  nlohmann::json j = summary_json(r);
  std::ofstream f(dir + "/summary.json");
  f << j.dump(1) << "\n";
  if (!f) throw std::runtime_error("cannot write " + dir + "/summary.json");
  return j;
}

}  // namespace rgnav::rgmap_pipeline
