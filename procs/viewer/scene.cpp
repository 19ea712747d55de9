#include "viewer/scene.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "viewer/json_geometry.h"
#include "viewer/region_json.h"

namespace rgnav::viewer {

namespace {

using nlohmann::json;
using geometry::Pose2;

const char* process_state_name(int s)
{
  // process_status_t::STATE_*
  static const char* names[] = {"stopped", "starting", "running", "hung", "backoff", "failed", "stopping"};
  return s >= 0 && s < 7 ? names[s] : "?";
}

const char* heartbeat_state_name(int s)
{
  // heartbeat_t::STATE_*
  static const char* names[] = {"starting", "running", "degraded", "stopping"};
  return s >= 0 && s < 4 ? names[s] : "?";
}

const char* path_status_name(int s)
{
  // global_path_t::STATUS_*
  static const char* names[] = {"on the way", "no path", "reached", "cancelled"};
  return s >= 0 && s < 4 ? names[s] : "?";
}


}  // namespace

Scene::Scene(SceneOptions options) : options_(options) {}

void Scene::set_map(rgmap::RgMap map)
{
  map_ = std::move(map);
  has_map_ = true;
  mark("map");
  mark("path");   // waypoints are placed through the regions' frames
}

void Scene::update_region(const rgmap::Region& region)
{
  if (rgmap::Region* held = map_.region(region.id)) {
    *held = region;
  } else {
    map_.insert_region(region);
  }
  map_.current_region = region.id;
  has_map_ = true;
  mark("map");
}

void Scene::set_graph(rgmap::RgGraph graph)
{
  graph_ = std::move(graph);
  mark("graph");
}

void Scene::set_pose(const RobotPoseView& pose)
{
  pose_ = pose;
  mark("pose");
}

void Scene::set_scan(ScanView scan)
{
  scan_ = std::move(scan);
  mark("scan");
}

void Scene::set_targets(TargetsView targets)
{
  targets_ = std::move(targets);
  mark("targets");
}

void Scene::set_trajectory(TrajectoryView trajectory)
{
  trajectory_ = std::move(trajectory);
  mark("trajectory");
}

void Scene::set_path(PathView path)
{
  path_ = std::move(path);
  mark("path");
}

void Scene::set_obstacles(ObstaclesView obstacles)
{
  obstacles_ = std::move(obstacles);
  mark("obstacles");
}

void Scene::set_supervisor(SupervisorView status)
{
  supervisor_ = std::move(status);
  mark("processes");
}

void Scene::add_heartbeat(const HeartbeatView& beat)
{
  const std::string key = beat.name + "@" + beat.host;
  auto it = heartbeats_.find(key);
  if (it == heartbeats_.end() && heartbeats_.size() >= options_.max_heartbeat_names) return;
  heartbeats_[key] = beat;
  mark("processes");
}

std::vector<Frame> Scene::take_changed(Clock::time_point now, int64_t now_wall_us)
{
  std::vector<Frame> out;
  const bool map_due = !map_sent_ || now - last_map_ >= options_.map_period;
  const bool status_due = !status_sent_ || now - last_status_ >= options_.status_period;
  for (auto it = dirty_.begin(); it != dirty_.end();) {
    const std::string& t = *it;
    json j;
    if (t == "map" || t == "graph") {
      if (!map_due) { ++it; continue; }
      j = t == "map" ? map_json() : graph_json();
    } else if (t == "processes") {
      if (!status_due) { ++it; continue; }
      j = processes_json(now_wall_us);
    } else if (t == "pose") {
      j = pose_json();
    } else if (t == "scan") {
      j = scan_json();
    } else if (t == "targets") {
      j = targets_json();
    } else if (t == "trajectory") {
      j = trajectory_json();
    } else if (t == "path") {
      j = path_json();
    } else if (t == "obstacles") {
      j = obstacles_json();
    }
    if (!j.is_null()) out.push_back({t, j.dump()});
    it = dirty_.erase(it);
  }
  for (const Frame& f : out) {
    if (f.topic == "map" || f.topic == "graph") {
      last_map_ = now;
      map_sent_ = true;
    }
  }
  // Rates and heartbeat ages change with time alone: sent on the status period.
  if (status_due) {
    if (!heartbeats_.empty() || supervisor_) {
      bool sent = false;
      for (const Frame& f : out) sent = sent || f.topic == "processes";
      if (!sent) out.push_back({"processes", processes_json(now_wall_us).dump()});
    }
    out.push_back({"rates", rates_json(now).dump()});
    last_status_ = now;
    status_sent_ = true;
  }
  return out;
}

json Scene::map_json() const
{
  json regions = json::array();
  for (const auto& [id, r] : map_.regions()) {
    if (r.state == rgmap::Region::State::kMerged) continue;   // drawn as the region it went into
    regions.push_back(region_json(r));
  }
  json gateways = json::array();
  for (const auto& [id, g] : map_.gateways()) {
    const rgmap::Region* a = map_.region(map_.resolve(g.region_a));
    if (!a) continue;
    json lines = json::array();
    for (const auto& [p, q] : rgmap::gateway_edges(g.gateway_points)) {
      json line = json::array();
      append_point(line, a->map_from_region * p);
      append_point(line, a->map_from_region * q);
      lines.push_back(std::move(line));
    }
    gateways.push_back({{"id", g.id},
                        {"class", static_cast<int>(g.cls)},
                        {"class_name", rgmap::to_string(g.cls)},
                        {"region_a", g.region_a},
                        {"region_b", g.region_b},
                        {"neutralized", g.neutralized},
                        {"lines", std::move(lines)}});
  }
  return {{"type", "map"},
          {"utime", map_.utime},
          {"version", map_.version},
          {"current_region", map_.current_region},
          {"regions", std::move(regions)},
          {"gateways", std::move(gateways)}};
}

json Scene::graph_json() const
{
  json edges = json::array();
  if (graph_) {
    std::map<int64_t, const rgmap::GraphNode*> nodes;
    for (const auto& n : graph_->nodes) nodes[n.id] = &n;
    auto place = [&](const rgmap::GraphNode& n) -> std::optional<Eigen::Vector2d> {
      const rgmap::Region* r = map_.region(map_.resolve(n.region_id));
      if (!r) return std::nullopt;
      return r->map_from_region * n.point;
    };
    for (const auto& e : graph_->edges) {
      auto a = nodes.find(e.from), b = nodes.find(e.to);
      if (a == nodes.end() || b == nodes.end()) continue;
      const auto pa = place(*a->second), pb = place(*b->second);
      if (!pa || !pb) continue;
      json edge = json::array();
      append_point(edge, *pa);
      append_point(edge, *pb);
      edge.push_back(e.kind == rgmap::GraphEdge::Kind::kGateway ? "gateway" : "region");
      edges.push_back(std::move(edge));
    }
  }
  return {{"type", "graph"}, {"map_version", graph_ ? graph_->map_version : 0}, {"edges", std::move(edges)}};
}

json Scene::pose_json() const
{
  if (!pose_) return nullptr;
  return {{"type", "pose"},
          {"utime", pose_->utime},
          {"source", pose_->source},
          {"pose", pose_array(pose_->map_from_base)},
          {"region_id", pose_->region_id},
          {"radius", options_.robot_radius}};
}

json Scene::scan_json() const
{
  // A scan is drawn from the newest pose: without one there is nowhere to put it.
  if (!scan_ || !pose_) return nullptr;
  json points = json::array();
  for (const auto& p : scan_->base_points) append_point(points, pose_->map_from_base * p);
  return {{"type", "scan"}, {"utime", scan_->utime}, {"points", std::move(points)}};
}

json Scene::targets_json() const
{
  if (!targets_ || !pose_) return nullptr;
  json points = json::array();
  for (const auto& t : targets_->odom_targets) points.push_back(pose_array(pose_->map_from_odom * t));
  return {{"type", "targets"}, {"utime", targets_->utime}, {"goal_id", targets_->goal_id}, {"targets", std::move(points)}};
}

json Scene::trajectory_json() const
{
  if (!trajectory_ || !pose_) return nullptr;
  json points = json::array();
  for (const auto& p : trajectory_->odom_points) append_point(points, pose_->map_from_odom * p);
  return {{"type", "trajectory"}, {"utime", trajectory_->utime}, {"points", std::move(points)}};
}

json Scene::path_json() const
{
  if (!path_) return nullptr;
  json points = json::array();
  for (const auto& w : path_->waypoints) {
    const rgmap::Region* r = map_.region(map_.resolve(w.region_id));
    if (r) append_point(points, (r->map_from_region * w.region_pose).translation());
  }
  return {{"type", "path"},
          {"utime", path_->utime},
          {"goal_id", path_->goal_id},
          {"status", path_->status},
          {"status_name", path_status_name(path_->status)},
          {"cost_s", r3(path_->cost_s)},
          {"reason", path_->reason},
          {"points", std::move(points)}};
}

json Scene::obstacles_json() const
{
  if (!obstacles_ || !pose_) return nullptr;
  json edges = json::array();
  const Pose2 map_from_base = pose_->map_from_odom * obstacles_->odom_from_base;
  for (const auto& [a, b] : obstacles_->base_edges) {
    json e = json::array();
    append_point(e, map_from_base * a);
    append_point(e, map_from_base * b);
    edges.push_back(std::move(e));
  }
  return {{"type", "obstacles"}, {"utime", obstacles_->utime}, {"edges", std::move(edges)}};
}

json Scene::processes_json(int64_t now_wall_us) const
{
  json alerts = json::array();
  json processes = json::array();
  if (supervisor_) {
    if (supervisor_->robot_held) alerts.push_back("robot held: a safety-critical process failed");
    if (!supervisor_->alert.empty()) alerts.push_back(supervisor_->alert);
    for (const auto& p : supervisor_->processes) {
      processes.push_back({{"name", p.name},
                           {"group", p.group},
                           {"state", process_state_name(p.state)},
                           {"pid", p.pid},
                           {"restarts", p.restarts},
                           {"last_exit", p.last_exit},
                           {"heartbeat_age_s", p.heartbeat_age_us < 0 ? -1.0 : r3(p.heartbeat_age_us * 1e-6)},
                           {"cpu_percent", r3(p.cpu_percent)},
                           {"rss_kb", p.rss_kb}});
      // process_status_t: HUNG 3, BACKOFF 4, FAILED 5.
      if (p.state >= 3 && p.state <= 5) alerts.push_back(p.name + " " + process_state_name(p.state));
    }
  }
  json beats = json::array();
  for (const auto& [key, b] : heartbeats_) {
    const double age_s = std::max(0.0, (now_wall_us - b.utime) * 1e-6);
    beats.push_back({{"name", b.name},
                     {"host", b.host},
                     {"state", heartbeat_state_name(b.state)},
                     {"age_s", r3(age_s)},
                     {"cpu_percent", r3(b.cpu_percent)},
                     {"rss_kb", b.rss_kb},
                     {"messages_in", b.messages_in},
                     {"messages_dropped", b.messages_dropped},
                     {"status", b.status}});
    // A stopping process is on its way out, not a fault.
    if (b.state != 3 && age_s > options_.heartbeat_alert_s) alerts.push_back(b.name + ": no heartbeat for " + std::to_string(static_cast<int>(age_s)) + " s");
    else if (b.state == 2) alerts.push_back(b.name + " degraded: " + b.status);
  }
  return {{"type", "processes"},
          {"host", supervisor_ ? supervisor_->host : ""},
          {"robot_held", supervisor_ ? supervisor_->robot_held : false},
          {"processes", std::move(processes)},
          {"heartbeats", std::move(beats)},
          {"alerts", std::move(alerts)}};
}

json Scene::rates_json(Clock::time_point now) const
{
  json streams = json::array();
  for (const auto& r : rates_.rates(now)) {
    streams.push_back({{"channel", r.channel}, {"hz", r3(r.hz)}, {"age_s", r3(r.age_s)}, {"count", r.count}, {"utime", r.utime}});
  }
  return {{"type", "rates"}, {"streams", std::move(streams)}};
}

}  // namespace rgnav::viewer
