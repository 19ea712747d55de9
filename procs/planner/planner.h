// The planner process's algorithm (diss. 5.4, 5.5.3), without LCM: takes the RG map, navigation
// goals, the robot's pose (region id + pose in the region frame + odometry pose at that time)
// and whether collision avoidance can pass; plans a route over the RG graph (global_planner.h),
// follows the robot's progress along it, and hands out
//   - the global path (per region waypoints, expected time, status with a reason) whenever it
//     changes, and
//   - targets 0.5-2 m apart in the odometry frame for collision avoidance, on every new route
//     and every resend period.
// Execution monitoring: a gateway crossed is timed and learned (EdgeCosts), so is a region
// crossed between two gateways. When collision avoidance reports it cannot pass and the robot
// made no progress for blocked_after_s: away from gateways, the place just ahead on the route is
// taken for an obstacle for a while (GlobalPlanner::block_place) and the goal's routes keep off
// it (round it, or NO_PATH); near the route's next gateway, a way round that gateway is taken
// (the gateway marked closed, its cost raised) only if it costs no more than waiting
// closed_after_s; else the robot waits on its route (a person standing in a doorway moves on),
// and after closed_after_s takes the way round, or the goal has NO_PATH; the goal stays, so that
// it is planned again when the closed mark expires or the map changes. Replans happen at most
// once per min_replan_period_s; a new route replaces a still valid one only when it is
// switch_gain cheaper than what is left of the old, so the robot does not oscillate between
// two routes. A goal where the robot stands that asks only for another heading is a turn on the
// spot (no path to plan: the robot may be cut off from its region's free space). Runs on message
// time (utime), never the wall clock.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "geometry/pose2.h"
#include "planner/global_planner.h"
#include "planner/planner_options.h"
#include "planner/route.h"
#include "rgmap/rg_map.h"

namespace rgnav::planner {

struct NavGoal
{
  int64_t goal_id = 0;
  int64_t region_id = 0;             // 0: by name
  std::string region_name;
  bool has_pose = false;             // false: anywhere suitable in the region
  geometry::Pose2 region_from_goal;
  double position_tolerance = 0.3;   // [m]
  double heading_tolerance = 3.2;    // [rad] >= pi: any heading
  bool beyond_known = false;         // the goal may lie in unknown space past the region's freespace (exploring)
};

struct RobotPose
{
  int64_t utime = 0;
  int64_t region_id = 0;
  geometry::Pose2 region_from_base;
  geometry::Pose2 odom_from_base;    // odometry pose at utime
};

enum class GoalStatus : int8_t { kNone = -1, kActive = 0, kNoPath = 1, kReached = 2, kCancelled = 3 };
const char* to_string(GoalStatus s);

struct PathReport
{
  int64_t utime = 0;
  int64_t goal_id = 0;
  GoalStatus status = GoalStatus::kNone;
  std::string reason;                // why NO_PATH / CANCELLED, or how the route was chosen
  Route route;                       // empty unless active
  double remaining_s = 0;            // [s] expected time left
  int64_t replans = 0;
};

struct TargetList
{
  int64_t utime = 0;
  int64_t goal_id = 0;
  std::vector<geometry::Pose2> odom_from_target;
  double max_speed = 0.5;
  bool final_is_goal = false;
};

class Planner
{
 public:
  explicit Planner(const PlannerOptions& options);

  void set_map(const rgmap::RgMap& map);
  // A new goal (a new goal_id replaces the running one); an unknown region or name gives NO_PATH.
  void set_goal(const NavGoal& goal, int64_t utime);
  void cancel(int64_t goal_id, int64_t utime);
  void on_pose(const RobotPose& pose);
  // Collision avoidance's state at utime: true while it stands without a way to its targets.
  void on_blocked(int64_t utime, bool blocked);
  // Names a region (operator): kept here as in the map, so a goal may use it at once.
  void name_region(int64_t region, const std::string& name);

  struct Output
  {
    std::optional<PathReport> path;      // publish GLOBAL_PATH
    std::optional<TargetList> targets;   // publish TARGETS
  };
  // Decides at message time utime (call on every pose and at least at the resend period).
  Output update(int64_t utime);

  GoalStatus status() const { return status_; }
  // Why the goal ended (NO_PATH, CANCELLED) or how its route was chosen.
  const std::string& reason() const { return reason_; }
  const std::optional<NavGoal>& goal() const { return goal_; }
  const Route& route() const { return route_; }
  int64_t replans() const { return replans_; }
  const PlanStats& last_stats() const { return last_stats_; }
  GlobalPlanner& global() { return global_; }
  const GlobalPlanner& global() const { return global_; }

 private:
  // Plans from the current pose; returns whether the route changed.
  bool replan(int64_t utime, const std::string& why);
  // A goal where the robot stands that asks only for another heading: the route of a turn on the spot.
  std::optional<Route> turn_on_the_spot() const;
  void finish(GoalStatus status, const std::string& reason, int64_t utime);
  // Progress: which leg the robot is on (by its region) and how far along; false if off route.
  bool track_progress();
  // On leg k from now on (k > the current leg): the gateways between learn how long they took.
  void enter_leg(size_t k, int64_t now);
  std::optional<TargetList> make_targets(int64_t utime) const;
  bool goal_reached() const;
  // The robot's pose in a region's frame: its own, or through the map frame for another region.
  std::optional<geometry::Pose2> pose_in_region(int64_t region) const;
  PlanRequest request_from_pose(int64_t utime) const;
  // Collision avoidance cannot pass and the robot makes no progress: replan, go round the next
  // gateway, or (no way round, for long enough) take it for closed.
  void handle_stuck(int64_t utime);
  // Resolves the goal's region and point in the current map (NO_PATH with a reason if it cannot).
  void resolve_goal();
  // The cost [s] of what is left of the route (its cost in proportion to the length left).
  double remaining_cost_s() const;
  // Every region and gateway of the route is still in the map.
  bool route_valid() const;
  // Keeps the robot's own track (places kTrackStep apart, execution.track_back_m long) from the pose.
  void record_track();
  // The track's places in `region`'s frame (through the map frame), newest first.
  std::vector<Eigen::Vector2d> track_in(int64_t region) const;

  PlannerOptions options_;
  GlobalPlanner global_;
  bool has_map_ = false;
  std::optional<NavGoal> goal_;
  int64_t goal_region_ = 0;
  Eigen::Vector2d goal_point_{0, 0};
  GoalStatus status_ = GoalStatus::kNone;
  std::string reason_;
  Route route_;
  size_t leg_ = 0;
  double along_ = 0;
  std::optional<RobotPose> pose_;
  int64_t leg_entered_utime_ = 0;         // when the robot entered the current leg's region
  int64_t gateway_reached_utime_ = 0;     // when the robot came within reach of the leg's exit
  bool blocked_ = false;
  int64_t blocked_since_ = 0;
  // Held at a blocked place: this goal's routes keep off blocked places (round them, or NO_PATH).
  bool strict_places_ = false;
  int64_t last_replan_utime_ = 0;
  int64_t progress_utime_ = 0;            // when the robot last got kProgressStep further along the route
  double progress_arc_ = 0;               // [m] how far along the route it was then
  int64_t last_stuck_check_utime_ = 0;
  bool replan_due_ = false;
  std::string replan_reason_;
  bool path_changed_ = false;
  int64_t last_targets_utime_ = 0;
  bool targets_due_ = false;
  int64_t replans_ = 0;
  int64_t map_version_ = 0;
  PlanStats last_stats_;
  struct TrackPlace
  {
    int64_t region = 0;
    Eigen::Vector2d point{0, 0};   // region frame
    double step = 0;               // [m] to the next older place
  };
  std::deque<TrackPlace> track_;   // newest first
  double track_length_ = 0;        // [m] sum of the steps
};

}  // namespace rgnav::planner
