// Node adapter of the explorer: RG_MAP (each new version replaces the one held), the robot's
// pose (POSE's map-frame pose while fresh, else SLAM_POSE), GATEWAY_HYPOTHESES (sightings taken
// to the map frame) and GLOBAL_PATH (the planner's status of the explorer's goals) in; NAV_GOAL
// (goals and cancels), REGION_NAME_REQUEST (finished regions, asked again every few seconds
// while the map has no name for them) and EXPLORER_STATUS (1 Hz and on every change of phase)
// out. The explorer runs on robot time: the newest stamp of its inputs, and a stamp far ahead
// counts only once a second input confirms it. Explorer::step runs on a wall-time timer at that
// robot time; a goal the planner has not answered is sent again. Explorer::save() is written
// to the state file (at once on a new goal or phase, else at most every persist.period_s of
// message time, and on exit) and restored on start.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "explorer/explorer.h"
#include "explorer/explorer_options.h"
#include "rgmap/rg_map.h"
#include "rgnav/gateway_hypotheses_t.hpp"
#include "rgnav/global_path_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "rgnav/slam_pose_t.hpp"
#include "runtime/node.h"
#include "time/robot_clock.h"

namespace rgnav::explorer {

// The node's own keys beside ExplorerNodeOptions (config/explorer.yaml: pose.*, step.*).
struct ExplorerNodeConfig
{
  ExplorerNodeOptions options;
  double pose_fresh_s = 1.0;        // [s] POSE preferred over SLAM_POSE while no older than this
  double step_period_s = 0.2;       // [s] wall time between calls of Explorer::step
};

// Reads config/explorer.yaml; throws config::ConfigError naming file and key.
// config_path: the explorer's config file; the planner's (view.planner_config) is read beside it
// for its grid. "" keeps the grid's defaults (tests).
ExplorerNodeConfig load_explorer_node_config(const config::Config& cfg, const config::RobotDescription& robot,
                                             const std::string& config_path = "");

// What the explorer reads and writes besides the bus (its command-line flags).
struct ExplorerFiles
{
  std::string state_file;   // --state-file: the stack, visited places, phase; "" = none
};

class ExplorerNode
{
 public:
  ExplorerNode(runtime::Node& node, ExplorerNodeConfig config, ExplorerFiles files = {});
  ~ExplorerNode();
  ExplorerNode(const ExplorerNode&) = delete;
  ExplorerNode& operator=(const ExplorerNode&) = delete;

  const Explorer& explorer() const { return explorer_; }
  bool restored() const { return restored_; }
  int64_t robot_utime() const { return clock_.now(); }
  int64_t saves() const { return saves_; }
  // Runs the explorer at the newest robot time and publishes what it decides (tests; the node
  // does this on its own every step.period_s).
  void step();
  void publish_status();

 private:
  void on_map(const rg_map_t& m);
  void on_pose(const region_pose_t& m);
  void on_slam_pose(const slam_pose_t& m);
  void on_hypotheses(const gateway_hypotheses_t& m);
  void on_global_path(const global_path_t& m);
  // Robot time: true when `utime` may be used (not a lone jump far ahead).
  bool observe_time(int64_t utime, const std::string& channel);
  void request_names();
  void restore();
  void save(bool now);
  void report();

  runtime::Node& node_;
  const ExplorerNodeConfig config_;
  const ExplorerFiles files_;
  Explorer explorer_;
  std::shared_ptr<const rgmap::RgMap> map_;
  int64_t map_version_ = -1;
  time::RobotClock clock_;                      // message time from the inputs' stamps
  int64_t last_pose_utime_ = 0;                 // POSE (the localizer's)
  int64_t last_any_pose_utime_ = 0;
  std::optional<ExploreGoal> sent_;             // the goal last sent, until the planner answers it
  bool sent_answered_ = false;
  int64_t reported_goal_ = 0;                   // GLOBAL_PATH last logged (goal, status)
  int8_t reported_status_ = -1;
  std::chrono::steady_clock::time_point sent_wall_{};
  std::map<int64_t, std::chrono::steady_clock::time_point> name_requests_;   // region -> last asked
  int64_t done_asked_version_ = -1;            // map version whose unnamed regions were queued once done
  Phase published_phase_ = Phase::kWaiting;
  bool restored_ = false;
  int64_t saves_ = 0;
  std::string saved_text_;
  int64_t last_saved_utime_ = 0;
  bool save_now_ = false;
  bool save_failed_ = false;
  std::string reported_text_;
  int8_t reported_state_ = -1;
};

}  // namespace rgnav::explorer
