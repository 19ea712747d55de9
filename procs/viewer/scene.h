// The viewer's scene: the newest of everything the page draws, held in plain C++ (no LCM), and
// turned into JSON text frames for the page, one per topic ("map", "pose", "scan", ...), all in
// the map frame so the page only draws. Frames go out only for topics that changed, the big
// map at most every map_period and the status tables at most every status_period, so a busy
// bus costs the page and the server a bounded number of frames per second.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rgmap/rg_graph.h"
#include "rgmap/rg_map.h"
#include "viewer/scene_types.h"
#include "viewer/stream_rates.h"

namespace rgnav::viewer {

struct SceneOptions
{
  double robot_radius = 0.26;                          // [m] the footprint drawn
  std::chrono::milliseconds map_period{1000};          // the map (and graph) frame at most this often
  std::chrono::milliseconds status_period{1000};       // processes, heartbeats and rates at most this often
  double heartbeat_alert_s = 2.0;                      // [s] a heartbeat older than this is an alert
  size_t max_heartbeat_names = 256;                    // distinct process names remembered
};

// One text frame for the page; `topic` is its "type" (the per-client queue keeps one per topic).
struct Frame
{
  std::string topic;
  std::string text;
};

class Scene
{
 public:
  using Clock = std::chrono::steady_clock;
  explicit Scene(SceneOptions options);

  void set_map(rgmap::RgMap map);
  // The current region as it grows (RG_REGION): replaces the region of that id in the map held,
  // or adds it (the page shows it before the next full map).
  void update_region(const rgmap::Region& region);
  void set_graph(rgmap::RgGraph graph);
  void set_pose(const RobotPoseView& pose);
  void set_scan(ScanView scan);
  void set_targets(TargetsView targets);
  void set_trajectory(TrajectoryView trajectory);
  void set_path(PathView path);
  void set_obstacles(ObstaclesView obstacles);
  void set_supervisor(SupervisorView status);
  void add_heartbeat(const HeartbeatView& beat);
  // Every accepted message, for the stream table.
  void note_message(const std::string& channel, int64_t utime, Clock::time_point at) { rates_.note(channel, utime, at); }

  // Frames of the topics that changed and are due; now_wall_us ages the heartbeats.
  std::vector<Frame> take_changed(Clock::time_point now, int64_t now_wall_us);

  // The frames themselves (tests, and a client that just connected).
  nlohmann::json map_json() const;
  nlohmann::json graph_json() const;
  nlohmann::json pose_json() const;
  nlohmann::json scan_json() const;
  nlohmann::json targets_json() const;
  nlohmann::json trajectory_json() const;
  nlohmann::json path_json() const;
  nlohmann::json obstacles_json() const;
  nlohmann::json processes_json(int64_t now_wall_us) const;
  nlohmann::json rates_json(Clock::time_point now) const;

  const rgmap::RgMap& map() const { return map_; }

 private:
  void mark(const char* topic) { dirty_.insert(topic); }

  const SceneOptions options_;
  rgmap::RgMap map_;
  bool has_map_ = false;
  std::optional<rgmap::RgGraph> graph_;
  std::optional<RobotPoseView> pose_;
  std::optional<ScanView> scan_;
  std::optional<TargetsView> targets_;
  std::optional<TrajectoryView> trajectory_;
  std::optional<PathView> path_;
  std::optional<ObstaclesView> obstacles_;
  std::optional<SupervisorView> supervisor_;
  std::map<std::string, HeartbeatView> heartbeats_;    // by "name@host"
  StreamRates rates_;
  std::set<std::string> dirty_;
  Clock::time_point last_map_{};
  Clock::time_point last_status_{};
  bool map_sent_ = false, status_sent_ = false;
};

}  // namespace rgnav::viewer
