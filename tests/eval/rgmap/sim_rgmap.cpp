#include "sim_rgmap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/step_order.h"
#include "sim/tour_planner.h"
#include "sim/waypoint_follower.h"

namespace rgnav::rgmap_pipeline {
namespace {

using Eigen::Vector2d;

geometry::Pose2 to_sm(const sim::Pose2& p) { return geometry::Pose2(p.x, p.y, p.theta); }

struct TimedTruth
{
  int64_t utime;
  sim::Pose2 pose;
};

// True pose at utime, interpolated between the simulator's odometry samples (which carry it);
// after the last sample extrapolated along the last two (a scan of the newest chunk can be
// newer than its odometry), where geometry::PoseTrack holds the last sample.
geometry::Pose2 truth_at(const std::vector<TimedTruth>& track, int64_t utime)
{
  auto it = std::lower_bound(track.begin(), track.end(), utime, [](const TimedTruth& t, int64_t u) { return t.utime < u; });
  if (it == track.end()) --it;
  if (it == track.begin() || it->utime == utime) return geometry::Pose2(it->pose.x, it->pose.y, it->pose.theta);
  const auto& a = *(it - 1);
  const auto& b = *it;
  const double s = static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime);
  const double dth = geometry::normalize_angle(b.pose.theta - a.pose.theta);
  return geometry::Pose2(a.pose.x + s * (b.pose.x - a.pose.x), a.pose.y + s * (b.pose.y - a.pose.y), a.pose.theta + s * dth);
}

}  // namespace

sensors::LaserScan as_laser_front(const sensors::LaserScan& s)
{
  sensors::LaserScan out = sensors::with_message_precision(s);
  out.scan_id = s.scan_id + 1;  // ids start at 1 like LASER_FRONT's
  return out;
}

SimRgMapRun run_sim_rgmap(sim::World world, const sim::SimulatorOptions& sim_options, LoadedPipeline loaded,
                          const SimTourOptions& options)
{
  SimRgMapRun res;
  if (!options.people) world.people.clear();
  res.world = world.name;
  const sim::Tour tour = sim::plan_tour(world, sim_options.robot);
  if (tour.waypoints.size() < 2) throw std::runtime_error(world.source + ": no tour through this world");
  res.visited = tour.visited;
  res.unreachable = tour.unreachable;
  res.tour_length_m = tour.length;
  const std::vector<sim::Vec2> route = sim::laps_route(tour, options.laps);

  const auto& l = sim_options.laser;
  loaded.options.mapper.base_from_laser = geometry::Pose2(l.mount_x, l.mount_y, l.mount_yaw);
  if (options.true_poses) loaded.options.poses_as_given = true;
  const double cpu0 = thread_cpu_seconds();
  RgMapPipeline pipeline(loaded.options, loaded.classifier);
  sim::SimulatorOptions simulated = sim_options;
  if (options.people) simulated.people_block_robot = false;   // seen, not met (SimTourOptions::people)
  sim::Simulator simulator(world, simulated);
  sim::WaypointFollower follower(route, [&simulator] { return simulator.truth(); });
  simulator.set_command_source(&follower);

  std::vector<TimedTruth> track;
  const std::chrono::microseconds chunk(static_cast<int64_t>(1e6 / l.rate_hz()));
  while (!follower.done()) {
    if (simulator.time_s() >= options.max_sim_s) {
      res.capped = true;
      break;
    }
    const double c0 = thread_cpu_seconds();
    const auto out = simulator.step(chunk);
    res.sim_cpu_seconds += thread_cpu_seconds() - c0;
    for (const auto& o : out.odometry) {
      track.push_back({o.utime, o.world_from_base});
      res.driven_m = o.true_distance;
      const Vector2d p(o.world_from_base.x, o.world_from_base.y);
      if (res.true_path.empty() || (p - res.true_path.back()).norm() >= 0.05) res.true_path.push_back(p);
    }
    if (options.true_poses) {
      // The true pose at each scan's time (the chunk's odometry samples, which carry it, are
      // in the track already), handed over as the given pose right before the scan.
      for (const auto& s : out.scans) {
        if (track.empty()) continue;   // no pose before the first odometry sample
        pipeline.add_odometry({s.utime, truth_at(track, s.utime)});
        pipeline.add_scan(as_laser_front(s));
      }
      continue;
    }
    sim::in_time_order(
        out, [&](const sim::OdometrySample& o) { pipeline.add_odometry({o.utime, to_sm(o.odom_from_base)}); },
        [&](const sensors::LaserScan& s) { pipeline.add_scan(as_laser_front(s)); });
  }
  res.sim_seconds = simulator.time_s();
  res.collisions = simulator.collisions();
  res.run = finish_run(pipeline);
  res.run.cpu_seconds = thread_cpu_seconds() - cpu0 - res.sim_cpu_seconds;
  res.run.log_seconds = res.sim_seconds;
  for (const auto& n : res.run.nodes) res.truth_at_node.push_back(truth_at(track, n.scan.utime));
  return res;
}

WorldScore score_world(const SimRgMapRun& run, const GroundTruth& truth, double gateway_match_distance,
                       const StaticSurfaces* statics)
{
  WorldScore s;
  std::vector<Vector2d> est, tru;
  for (size_t k = 0; k < run.run.nodes.size() && k < run.truth_at_node.size(); ++k) {
    const auto& m = run.run.nodes[k].map_from_base;
    est.push_back(m.translation());
    tru.push_back(run.truth_at_node[k].translation());
  }
  s.world_from_map = fit_rigid(est, tru);
  double se = 0;
  for (size_t k = 0; k < est.size(); ++k) se += (s.world_from_map * est[k] - tru[k]).squaredNorm();
  s.alignment_rmse_m = est.empty() ? 0.0 : std::sqrt(se / static_cast<double>(est.size()));

  s.counts = count_map(run.run.map, run.run.kernel_stats.raw_points);
  if (statics) s.ghosts = count_ghost_segments(run.run.map, s.world_from_map, *statics);
  // As Bormann et al.'s evaluation: segments and rooms of <= 0.25 m^2 left out (rgmap_metrics.h).
  const int64_t min_cells = min_segment_cells(truth.rooms);
  const LabelGrid room_grid = without_small_rooms(truth.rooms, min_cells);
  const RegionCells cells = without_small_regions(region_cells(run.run.map, s.world_from_map, room_grid), min_cells);
  s.segmentation = score_segmentation(room_grid, cells);
  std::map<int64_t, std::vector<Vector2d>> positions;
  for (const auto& [id, ps] : run.run.robot_positions)
    for (const auto& p : ps) positions[id].push_back(s.world_from_map * p);
  s.segmentation_diagnosis = diagnose_segmentation(room_grid, cells, positions);

  // Rooms the tour explored: the planned tour's rooms.
  std::vector<int32_t> rooms;
  for (const auto& name : run.visited)
    if (const int32_t l = truth.label_of(name)) rooms.push_back(l);
  std::sort(rooms.begin(), rooms.end());
  const std::set<int32_t> explored(rooms.begin(), rooms.end());

  std::vector<Vector2d> found;
  for (const auto& p : gateway_positions(run.run.map)) found.push_back(s.world_from_map * p);
  std::vector<Vector2d> between, crossed;
  // Gateways of the explored part: every room it joins explored (a dead end: its one room).
  for (const auto& g : truth.gateways) {
    bool all = !g.rooms.empty();
    for (int32_t r : g.rooms) all = all && explored.count(r);
    if (all) between.push_back(g.center());
  }
  for (int k : crossed_gateways(truth, run.true_path)) crossed.push_back(truth.gateways[static_cast<size_t>(k)].center());
  s.gateways = match_gateways(between, found, gateway_match_distance);
  s.gateway_truth_positions = between;
  s.gateway_found_positions = found;
  s.gateways_crossed = match_gateways(crossed, found, gateway_match_distance);

  std::map<int64_t, int64_t> to_room;
  for (const auto& [region, room] : s.segmentation.region_to_room) to_room[region] = room;
  s.graph = compare_graphs(truth_graph(truth, rooms), region_graph(run.run.map), to_room);
  return s;
}

nlohmann::json to_json(const SimRgMapRun& r, const WorldScore& s)
{
  const auto& seg = s.segmentation;
  const auto& g = s.graph;
  nlohmann::json j;
  j["seg_precision"] = seg.precision;
  j["seg_recall"] = seg.recall;
  j["seg_recall_full"] = seg.recall_full;
  j["seg_jaccard"] = seg.jaccard;
  j["seg_coverage"] = seg.coverage;
  j["seg_loss_seen_through"] = s.segmentation_diagnosis.seen_loss;
  j["seg_loss_driven_through"] = s.segmentation_diagnosis.driven_loss;
  j["rooms_truth"] = seg.rooms;
  j["rooms_explored"] = seg.rooms_explored;
  j["rooms_visited_by_tour"] = static_cast<int>(r.visited.size());
  j["over_segmented_rooms"] = seg.over_segmented;
  j["under_segmented_regions"] = seg.under_segmented;
  j["regions_outside_rooms"] = seg.regions_outside;
  j["gateways_truth"] = s.gateways.truth;
  j["gateways_matched"] = s.gateways.matched;
  j["gateways_missed"] = s.gateways.missed;
  j["gateways_false"] = s.gateways.false_positives;
  j["gateway_error_m"] = s.gateways.mean_error_m;
  j["gateways_crossed"] = s.gateways_crossed.truth;
  j["gateways_crossed_matched"] = s.gateways_crossed.matched;
  j["graph_isomorphic"] = g.isomorphic;
  j["graph_truth_nodes"] = g.truth_nodes;
  j["graph_truth_edges"] = g.truth_edges;
  j["graph_map_nodes"] = g.map_nodes;
  j["graph_map_edges"] = g.map_edges;
  j["graph_node_difference"] = g.map_nodes - g.truth_nodes;
  j["graph_edge_difference"] = g.map_edges - g.truth_edges;
  j["graph_edges_matched"] = g.edges_matched;
  j["graph_edges_missing"] = g.edges_missing;
  j["graph_edges_extra"] = g.edges_extra;
  j["graph_edges_internal"] = g.edges_internal;
  j["graph_rooms_unmatched"] = g.rooms_unmatched;
  const auto& c = s.counts;
  j["regions"] = c.regions;
  j["merged_regions"] = c.merged;
  j["gateways"] = c.gateways;
  j["doors"] = c.doors;
  j["neutralized"] = c.neutralized;
  j["segments"] = c.segments;
  j["ghost_segments"] = s.ghosts.ghosts;
  j["ghost_segment_m"] = s.ghosts.ghost_length_m;
  j["compression"] = c.compression;
  add_fidelity_json(r.run.fidelity, &j);
  j["mean_region_bytes"] = c.mean_region_bytes;
  j["consistency_problems"] = c.consistency_problems;
  j["overlapping_regions"] = c.overlapping_regions;
  j["alignment_rmse_m"] = s.alignment_rmse_m;
  j["tour_length_m"] = r.tour_length_m;
  j["driven_m"] = r.driven_m;
  j["sim_seconds"] = r.sim_seconds;
  j["capped"] = r.capped;
  j["collisions"] = r.collisions;
  j["accepted_scans"] = r.run.mapper_stats.accepted;
  j["loop_closures"] = r.run.mapper_stats.loop_closures;
  j["pipeline_cpu_seconds"] = r.run.cpu_seconds;
  j["simulator_cpu_seconds"] = r.sim_cpu_seconds;
  j["realtime_factor"] = r.run.cpu_seconds > 0 ? r.sim_seconds / r.run.cpu_seconds : 0.0;
  return j;
}

}  // namespace rgnav::rgmap_pipeline
