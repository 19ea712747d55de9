// Node adapter of the planner: RG_MAP (or a saved map loaded at start), POSE / SLAM_POSE carried
// forward by ODOMETRY (pose_source.h), NAV_GOAL, REGION_NAME and CA_STATUS in; GLOBAL_PATH and
// TARGETS out. The planner runs on robot time: the newest stamp of the robot's own streams
// (poses, odometry, collision avoidance, the map), never the wall-clock stamps of the
// operator's tools, and a stamp far ahead of it counts only once a second input confirms it (a
// corrupted stamp must not age every pose at once). planner.update() runs on every pose and
// every 100 ms; GLOBAL_PATH goes out whenever it changes and again every second while a goal is
// pursued (with the time left recomputed from the newest pose), so a tool that starts
// listening late still hears it. The learned costs, the region names and the running goal are
// saved to the state file (goal and names at once, learned costs at most every
// persist.period_s of message time, everything on exit); a restarted planner takes its goal up
// again. Goal, status and replans go into the heartbeat status.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "planner/planner.h"
#include "planner/planner_options.h"
#include "planner/pose_source.h"
#include "rgmap/rg_map.h"
#include "rgnav/ca_status_t.hpp"
#include "rgnav/nav_goal_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/region_name_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "rgnav/slam_pose_t.hpp"
#include "runtime/node.h"
#include "time/robot_clock.h"

namespace rgnav::planner {

// The node's own keys beside PlannerNodeOptions (config/planner.yaml: channels.odometry, pose.*).
struct PlannerNodeConfig
{
  PlannerNodeOptions options;
  std::string odometry = "ODOMETRY";    // "" = poses are not carried forward
  PoseSourceOptions pose;
  double odometry_period_s = 0.1;       // [s] carried poses handed to the planner at most this often
};

// Reads config/planner.yaml; throws config::ConfigError naming file and key.
PlannerNodeConfig load_planner_node_config(const config::Config& cfg, const config::RobotDescription& robot);

// What the planner reads and writes besides the bus (its command-line flags).
struct PlannerFiles
{
  std::string map;          // --map: an rgmap.json or a folder holding one; "" = wait for RG_MAP
  std::string state_file;   // --state-file: learned costs, names, the running goal; "" = none
};

class PlannerNode
{
 public:
  // Throws config::ConfigError when files.map cannot be loaded (the process refuses to start).
  PlannerNode(runtime::Node& node, PlannerNodeConfig config, PlannerFiles files = {});
  ~PlannerNode();
  PlannerNode(const PlannerNode&) = delete;
  PlannerNode& operator=(const PlannerNode&) = delete;

  const Planner& planner() const { return planner_; }
  // The goal taken up again from the state file (set once a map was there to pursue it in).
  const std::optional<NavGoal>& resumed_goal() const { return resumed_goal_; }
  const std::map<int64_t, std::string>& names() const { return names_; }
  int64_t saves() const { return saves_; }
  int64_t robot_utime() const { return clock_.now(); }
  // Runs the planner at the newest robot time and publishes what it decides (tests; the node
  // does this on its own on every pose and every 100 ms).
  void step();

 private:
  void on_map(const rg_map_t& m);
  void take_map(const rgmap::RgMap& map, const std::string& source);
  void on_pose(const region_pose_t& m);
  void on_slam_pose(const slam_pose_t& m);
  void place_slam_pose(const slam_pose_t& m);
  void on_odometry(const odometry_t& m);
  void on_goal(const nav_goal_t& m);
  void on_region_name(const region_name_t& m);
  void on_ca_status(const ca_status_t& m);
  // Robot time: true when `utime` may be used (not a lone jump far ahead).
  bool observe_time(int64_t utime, const std::string& channel);
  void take_pose(const RobotPose& pose);
  void step_at(int64_t utime);
  void republish_path();
  void restore();
  // Saves when something changed: the goal and names at once, learned costs when due.
  void save(bool now);
  void report();

  runtime::Node& node_;
  const PlannerNodeConfig config_;
  const PlannerFiles files_;
  Planner planner_;
  PoseSource poses_;
  bool has_map_ = false;
  int64_t map_version_ = -1;
  std::map<int64_t, std::string> names_;        // the operator's names, laid over every map
  time::RobotClock clock_;                      // message time from the inputs' stamps
  int64_t last_odometry_seq_ = -1;
  int64_t last_odometry_utime_ = 0;
  int64_t last_carried_utime_ = 0;
  std::optional<RobotPose> last_pose_;
  std::optional<slam_pose_t> slam_before_map_;  // the scan mapper's pose heard before the first map
  std::optional<NavGoal> resume_goal_;          // from the state file, until a map is there
  std::optional<NavGoal> resumed_goal_;
  std::optional<PathReport> last_path_;         // republished while the goal is pursued
  int republish_after_end_ = 0;                 // a final status is repeated this many times more
  int64_t saves_ = 0;
  bool goal_dirty_ = false;                     // goal or names changed since the last save
  int64_t saved_cost_changes_ = 0;
  int64_t last_saved_utime_ = 0;
  std::chrono::steady_clock::time_point last_save_wall_{};
  bool save_failed_ = false;
  std::string reported_text_;
  int8_t reported_state_ = -1;
};

}  // namespace rgnav::planner
