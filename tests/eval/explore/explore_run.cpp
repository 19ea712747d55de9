#include "explore_run.h"

#include "vision_stand_in.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "drive_loop.h"
#include "geometry/pose_track.h"
#include "offline_run.h"
#include "sim/tour_planner.h"
#include "sim_rgmap.h"

namespace rgnav::explore_eval {

namespace rp = rgmap_pipeline;
using Eigen::Vector2d;
using geometry::Pose2;

namespace {

Pose2 to_pose(const sim::Pose2& p) { return Pose2(p.x, p.y, p.theta); }

}  // namespace

WorldTruth world_truth(const std::string& name, sim::World world, const sim::RobotOptions& robot)
{
  WorldTruth w;
  w.name = name;
  w.truth = rp::ground_truth_of(world);
  w.raster.width = w.truth.rooms.width;
  w.raster.height = w.truth.rooms.height;
  w.raster.resolution = w.truth.rooms.resolution;
  w.raster.origin = w.truth.rooms.origin;
  w.clearance = world_clearance(world, w.raster, robot.height, robot.ground_clearance, WorldTruth::kClearanceSearch);
  w.world = std::move(world);
  return w;
}

StartTruth start_truth(const WorldTruth& w, const sim::Pose2& start, const std::string& label, const sim::RobotOptions& robot)
{
  StartTruth s;
  s.label = label;
  s.start = start;
  // The tour planner's margin: what it calls standable is what the reachable area is made of.
  const auto area = reachable_area(w.raster, w.clearance, Vector2d(start.x, start.y), robot.radius, sim::TourOptions{}.margin);
  if (!area) throw std::runtime_error(w.name + " " + label + ": the robot cannot stand at its start");
  s.area = *area;
  sim::World world = w.world;
  world.start = start;
  const sim::Tour tour = sim::plan_tour(world, robot);
  s.reachable_rooms = tour.visited;
  s.unreachable_rooms = tour.unreachable;
  s.tour_length_m = tour.length;
  return s;
}

RunResult run_exploration(const WorldTruth& w, const StartTruth& start, ExploreDriver& driver, const RunSetup& setup,
                          uint64_t seed, const std::string& map_dir)
{
  const auto wall0 = std::chrono::steady_clock::now();
  RunResult res;
  res.method = driver.method();
  res.start = start.label;
  sim::World world = w.world;
  world.start = start.start;
  sim::SimulatorOptions so = setup.sim;
  so.seed = seed;
  plan_eval::DriveLoop loop(world, so, setup.lld, setup.ca);
  auto loaded = setup.pipeline;
  const auto& l = so.laser;
  const Pose2 base_from_laser(l.mount_x, l.mount_y, l.mount_yaw);
  loaded.options.mapper.base_from_laser = base_from_laser;
  rp::RgMapPipeline pipeline(loaded.options, loaded.classifier);

  geometry::PoseTrack truth_track;
  std::vector<Vector2d> true_path;
  SeenArea seen(w.raster, start.area.free);
  std::set<int32_t> reachable_labels, entered_labels;
  for (const auto& name : start.reachable_rooms)
    if (const int32_t l = w.truth.label_of(name)) reachable_labels.insert(l);
  std::optional<Pose2> last_seen_pose;
  int64_t last_seen_utime = 0;
  int64_t aligned = 0;
  double next_trace = 0;
  std::optional<VisionStandIn> vision;
  if (setup.vision) vision.emplace(w.world, VisionStandInOptions{});

  while (true) {
    const double t = loop.sim().time_s();
    if (t >= setup.max_sim_s) {
      res.timed_out = true;
      break;
    }
    const sim::StepOutput& out = loop.sense();
    if (vision && vision->due(t) && loop.ready())
      loop.obstacle_points(loop.sim().now_utime(), vision->update(t, loop.truth(), loop.odometry().pose));
    for (const auto& o : out.odometry) {
      truth_track.add(o.utime, to_pose(o.world_from_base));
      const Vector2d p(o.world_from_base.x, o.world_from_base.y);
      if (true_path.empty() || (p - true_path.back()).norm() >= 0.05) true_path.push_back(p);
      const int64_t i = w.raster.index_of(p);
      if (i >= 0)
        if (const int32_t label = w.truth.rooms.labels[static_cast<size_t>(i)]; label > 0) entered_labels.insert(label);
    }
    // Odometry before the scans of the same step, as a bus would deliver them by time.
    size_t oi = 0;
    for (const auto& s : out.scans) {
      for (; oi < out.odometry.size() && out.odometry[oi].utime <= s.utime; ++oi)
        pipeline.add_odometry({out.odometry[oi].utime, to_pose(out.odometry[oi].odom_from_base)});
      // The area seen: the scan at its true laser pose, when the robot moved or turned or half a
      // second passed (a 75 Hz laser sees the same cells many times over).
      if (const auto truth = truth_track.at(s.utime)) {
        const bool moved = !last_seen_pose || (truth->translation() - last_seen_pose->translation()).norm() > 0.1 ||
                           std::abs(geometry::normalize_angle(truth->theta() - last_seen_pose->theta())) > 0.09 ||
                           s.utime - last_seen_utime > 500'000;
        if (moved) {
          seen.add_scan(*truth * base_from_laser, s, setup.seen_range_m);
          last_seen_pose = *truth;
          last_seen_utime = s.utime;
          if (std::isnan(res.time_to_90_s) && seen.ratio() >= 0.9) res.time_to_90_s = loop.sim().time_s();
        }
      }
      pipeline.add_scan(rp::as_laser_front(s));
      if (pipeline.counts().aligned != aligned) {
        aligned = pipeline.counts().aligned;
        driver.on_aligned(pipeline);
      }
    }
    for (; oi < out.odometry.size(); ++oi) pipeline.add_odometry({out.odometry[oi].utime, to_pose(out.odometry[oi].odom_from_base)});
    if (!loop.ready()) continue;
    if (loop.sim().time_s() < setup.spin_at_start_s) {
      loop.command(0.0, 0.5);
      continue;
    }
    const auto* node = pipeline.last_aligned();
    if (node) {
      PipelineView view{pipeline, loop.sim().now_utime(), Pose2(), loop.odometry().pose, loop.cannot_pass()};
      // The scan mapper's estimate of its newest scan carried forward by odometry since.
      view.map_from_base = node->map_from_base * node->odom_from_base.inverse() * loop.odometry().pose;
      if (auto targets = driver.step(view)) loop.set_targets(*targets);
      if (setup.trace && loop.sim().time_s() >= next_trace) {
        next_trace += 1.0;
        std::ostringstream line;
        line << std::fixed << std::setprecision(2) << w.name << " " << start.label << " " << driver.method()
             << " t=" << loop.sim().time_s() << " at " << loop.truth().x() << "," << loop.truth().y() << " slam "
             << view.map_from_base.x() << "," << view.map_from_base.y() << " ca "
             << collision_avoidance::mode_name(loop.ca().mode()) << " (" << loop.ca().status() << ", target "
             << loop.ca().next_target() << ") person " << std::min(loop.nearest_person(), 99.0) << " seen " << seen.ratio() << " rooms "
             << entered_labels.size() << "/" << reachable_labels.size() << " | " << driver.trace_line();
        std::cerr << line.str() << "\n";
      }
      if (driver.done()) {
        res.ended_done = true;
        break;
      }
    }
    loop.act();
  }

  res.sim_s = loop.sim().time_s();
  res.driven_m = loop.true_distance();
  res.collisions = loop.sim().collisions();
  res.contacts = loop.take_contacts();
  res.area_seen_ratio = seen.ratio();
  res.rooms_reachable = static_cast<int>(reachable_labels.size());
  for (const int32_t l : reachable_labels) {
    if (entered_labels.count(l)) ++res.rooms_entered;
    else res.rooms_missed.push_back(w.truth.room_names[static_cast<size_t>(l - 1)]);
  }
  res.premature = res.ended_done && (res.rooms_entered < res.rooms_reachable || res.area_seen_ratio < 0.9);

  // The explored map scored as the rgmap bench scores a tour's.
  rp::SimRgMapRun run;
  run.world = w.name;
  for (const int32_t l : entered_labels) run.visited.push_back(w.truth.room_names[static_cast<size_t>(l - 1)]);
  run.tour_length_m = start.tour_length_m;
  run.sim_seconds = res.sim_s;
  run.driven_m = res.driven_m;
  run.collisions = res.collisions;
  run.capped = res.timed_out;
  run.run = rp::finish_run(pipeline);
  for (const auto& n : run.run.nodes) run.truth_at_node.push_back(truth_track.at(n.scan.utime).value_or(Pose2()));
  run.true_path = true_path;
  nlohmann::json map_json;
  if (run.run.map.regions().empty()) {
    map_json = {{"error", "no region"}};
  } else {
    const auto score = rp::score_world(run, w.truth, setup.gateway_match_m);
    res.seg_precision = score.segmentation.precision;
    res.seg_recall = score.segmentation.recall;
    map_json = rp::to_json(run, score);
    if (!map_dir.empty()) rp::write_run_outputs(run.run, loaded.options, map_dir);
  }
  res.detail = {{"driver", driver.stats()}, {"map", map_json}};
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

nlohmann::json to_json(const RunResult& r)
{
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json j = {{"method", r.method},
                      {"start", r.start},
                      {"ended_done", r.ended_done},
                      {"timed_out", r.timed_out},
                      {"premature_end", r.premature},
                      {"rooms_reachable", r.rooms_reachable},
                      {"rooms_entered", r.rooms_entered},
                      {"rooms_entered_ratio", r.rooms_reachable > 0 ? static_cast<double>(r.rooms_entered) / r.rooms_reachable : 1.0},
                      {"rooms_missed", r.rooms_missed},
                      {"area_seen_ratio", r.area_seen_ratio},
                      {"time_to_90_s", num(r.time_to_90_s)},
                      {"time_s", r.sim_s},
                      {"driven_m", r.driven_m},
                      {"collisions", r.collisions},
                      {"seg_precision", num(r.seg_precision)},
                      {"seg_recall", num(r.seg_recall)},
                      {"wall_s", r.wall_s}};
  if (!r.contacts.empty()) j["contacts"] = r.contacts;
  j["detail"] = r.detail;
  return j;
}

}  // namespace rgnav::explore_eval
