// The explorer (diss. 5.0's high-level planning, ch. 7): explores an unknown building region by
// region. Inside the current region it goes to the frontiers of the region's freespace
// (frontiers.h), nearest first, each looked at from a view point the planner can reach
// (view_point.h; a frontier with none is no goal for now, nor one a look past would show little
// unknown through: view_gain.h), until none is left (the region is complete); then it takes the
// next untraversed gateway from the stack (gateway_stack.h), breadth-first, and drives through
// it, aimed through the opening the map's lines show beside the detector's crossing point (an
// entry they show no opening for is set aside until the map near it changes: opening.h); a
// region left incomplete is gone back to once the current one is complete and no gateway is
// waiting. It ends when no frontier of any region and no stacked gateway is left that it can
// still try. Goals go to the planner (NAV_GOAL); a goal beyond a gateway lies in unknown space
// and is sent with beyond_known (the planner drives from the nearest known free place straight
// on). Regions the robot has finished are offered for naming. The robot first looks behind (its
// laser sees the half ahead); when the planner answers that the robot's own place joins nothing
// ("start cut off", planner/no_path_reason.h), or when everything left failed from where it
// stands, it looks behind again, then steps back along its own track (RecoveryOptions), instead
// of standing where nothing changes; a goal only a gateway taken for closed is in the way of
// counts no failed attempt (but waits longer each time, and max_closed_retries set it aside). A
// goal the robot gets no nearer to in progress_timeout_s fails; such a failure counts against
// the goal only if the robot arrived somewhere since the last one (a robot held where it stands
// fails every goal, and is not done for that). A frontier that failed, the current region's too,
// waits until the stack is empty.
//
// Pure algorithm, message time only: the node feeds it the RG map, the robot's pose, the
// detector's gateway sightings and the planner's goal status, and calls step() at its own pace.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "explorer/explorer_options.h"
#include "explorer/frontiers.h"
#include "explorer/gateway_stack.h"
#include "explorer/last_failure.h"
#include "explorer/place_view.h"
#include "geometry/pose2.h"
#include "planner/global_planner.h"
#include "rgmap/rg_map.h"

namespace rgnav::explorer {

struct RobotPose
{
  int64_t utime = 0;
  geometry::Pose2 map_from_base;   // the RG map's frame (the scan mapper's or the localizer's)
};

// A goal for the planner (NAV_GOAL), in a region's frame.
struct ExploreGoal
{
  // kLook: a turn on the spot to see behind; kStep: back along the robot's own track (both to
  // change the view of a robot whose place the planner finds cut off: RecoveryOptions).
  enum class Kind : int8_t { kFrontier = 1, kGateway = 2, kRegion = 3, kLook = 4, kStep = 5 };
  int64_t goal_id = 0;
  Kind kind = Kind::kFrontier;
  int64_t region_id = 0;
  Eigen::Vector2d region_point{0, 0};
  double heading = 0;              // [rad] region frame
  double heading_tolerance = 4.0;  // [rad] >= pi: any heading
  double tolerance = 0.5;          // [m]
  bool beyond_known = false;       // the point may lie in unknown space past the region's freespace
  int64_t entry_id = 0;            // kGateway: the stack entry
  Eigen::Vector2d map_point{0, 0}; // the same point in the map frame
  Eigen::Vector2d frontier_point{0, 0};   // map frame: kFrontier / kRegion: the frontier looked at (else map_point)
};

const char* to_string(ExploreGoal::Kind k);

// What the planner says of a goal (GLOBAL_PATH's status).
enum class GoalOutcome : int8_t { kActive = 0, kNoPath = 1, kReached = 2, kCancelled = 3 };

enum class Phase : int8_t { kWaiting = 0, kExploring = 1, kDone = 2 };
const char* to_string(Phase p);

// step()'s order to the node: send `goal`, or cancel the running goal, or nothing.
struct Command
{
  std::optional<ExploreGoal> goal;
  bool cancel = false;
  int64_t cancel_goal_id = 0;
};

struct ExplorerStatus
{
  Phase phase = Phase::kWaiting;
  std::string activity;            // what it does now, for people ("frontier 2.1 m wide in region 3", "done: ...")
  int64_t current_region = 0;
  double current_completeness = 0;
  int regions = 0, complete_regions = 0;
  int stack_pending = 0, stack_done = 0, stack_set_aside = 0;
  int goals_sent = 0, goals_reached = 0, goals_failed = 0;
  std::optional<ExploreGoal> goal;
};

class Explorer
{
 public:
  explicit Explorer(ExplorerOptions options = {});

  // The newest RG map (its current_region is where the robot is).
  void set_map(std::shared_ptr<const rgmap::RgMap> map);
  void set_pose(const RobotPose& pose);
  // Sightings of the gateway detector at utime, map frame.
  void add_sightings(const std::vector<GatewaySighting>& sightings, int64_t utime);
  // The planner's status of goal `goal_id` (ignored for any goal but the running one); a NO_PATH's
  // reason begins with its cause (planner/no_path_reason.h).
  void goal_report(int64_t goal_id, GoalOutcome outcome, const std::string& reason, int64_t utime);

  // Decides; at most once per decide_period_s unless something ended the running goal.
  Command step(int64_t utime);

  ExplorerStatus status() const;
  Phase phase() const { return phase_; }
  // The running goal (status() has it too, but works out every region's frontiers for the rest).
  const std::optional<ExploreGoal>& goal() const { return goal_; }
  const GatewayStack& stack() const { return stack_; }
  // How the last goal ended: "reached", "no progress", "timed out", "no path: <reason>", ...
  const std::string& last_end() const { return last_end_; }
  // Goals reached and failed so far (status() has them too, but works out every region's frontiers).
  std::pair<int, int> goal_counts() const { return {goals_reached_, goals_failed_}; }
  // The region's frontiers that are goals of its own: those at a stacked gateway's opening are not.
  std::vector<Frontier> open_frontiers(int64_t region_id) const;
  // Regions finished since the last call (complete and left, or all at the end), for naming.
  std::vector<int64_t> take_finished_regions();

  // Everything a restarted explorer needs to go on where it was: the stack, visited frontier
  // places, the start region, the phase, the goal counter.
  nlohmann::json save() const;
  // Throws std::invalid_argument on a malformed document.
  void restore(const nlohmann::json& j);

 private:
  std::optional<ExploreGoal> choose(int64_t utime);
  // The nearest frontier of the region to look at (untried_only: none that failed before).
  std::optional<ExploreGoal> frontier_goal(int64_t region_id, int64_t utime, bool untried_only = false);
  std::optional<ExploreGoal> gateway_goal(int64_t utime);
  // Where a goal through stack entry `e` crosses: the opening the map's lines show beside its
  // crossing point; nothing when they show none the robot fits through (opening.h).
  std::optional<Eigen::Vector2d> opening_of(const StackEntry& e) const;
  // Entries pending or due again that the map shows no opening for are set aside for good (until
  // the map near them changes): a gap between furniture, a wall or a corner taken for a door is
  // no way on.
  void set_aside_closed_entries(int64_t utime);
  // The nearest frontier of a live region other than `current` (kind kRegion).
  std::optional<ExploreGoal> other_region_goal(int64_t current, int64_t utime, bool untried_only);
  bool goal_still_open() const;
  // [us] How long a goal waits after its k-th failure behind a gateway held closed (k >= 1).
  int64_t closed_retry_wait_us(int k) const;
  // Numbers `g` and makes it the running goal (its progress counted from now).
  void start_goal(ExploreGoal* g, int64_t utime);
  // kStartCutOff: the robot's own place joins nothing (not the goal's fault); kClosedGateway: only
  // a gateway taken for closed for a while is in the way (no attempt of the goal's either).
  void end_goal(bool reached, const std::string& reason, int64_t utime, bool start_cut_off = false,
                bool behind_closed = false);
  // The robot's place is cut off: a look behind, else a step back along its track, else nothing
  // (looked and stepped from here already).
  std::optional<ExploreGoal> recovery_goal() const;
  enum class Recovery : int8_t { kNone, kLook, kStep };
  // What is due at `here`: a look unless one began near here, else a step back unless one began
  // near here, else nothing.
  Recovery recovery_from(const Eigen::Vector2d& here) const;
  bool is_recovery(const ExploreGoal& g) const
  {
    return g.kind == ExploreGoal::Kind::kLook || g.kind == ExploreGoal::Kind::kStep;
  }
  // The pieces of region `region_id`'s planner grid the robot can drive to: the main one, and the
  // one it stands in when it is in that region.
  std::vector<int32_t> reachable_pieces(int64_t region_id, const planner::RegionGrid& grid) const;
  bool visited(const Eigen::Vector2d& map_point) const;
  bool failed_here(const Eigen::Vector2d& map_point, int64_t utime) const;
  bool failed_before(const Eigen::Vector2d& map_point) const;
  // Something set aside will be due again: not done yet.
  bool waiting_to_retry(int64_t utime) const;
  // Goals set aside for good whose surroundings changed since they failed are due again.
  void release_changed(int64_t utime);

  ExplorerOptions options_;
  std::shared_ptr<const rgmap::RgMap> map_;
  // The planner's grids of the map's regions (only its region planners are used: where the
  // robot fits and which free space joins which).
  planner::GlobalPlanner grids_;
  std::optional<RobotPose> pose_;
  GatewayStack stack_;
  Phase phase_ = Phase::kWaiting;
  int64_t start_region_ = 0;
  int64_t next_goal_id_ = 1;
  std::optional<ExploreGoal> goal_;
  int64_t goal_sent_utime_ = 0;
  double goal_best_distance_ = 0;               // [m] the robot's nearest to the running goal so far ...
  int64_t goal_progress_utime_ = 0;             // ... and when it last got progress_m nearer
  int64_t last_decision_utime_ = 0;
  bool decide_now_ = true;
  std::vector<Eigen::Vector2d> visited_;        // map frame: frontier goals reached
  struct FailedPlace
  {
    Eigen::Vector2d map_point;
    int64_t retry_utime = 0;
    int attempts = 0;
    int closed_failures = 0;        // failures only a gateway held closed was in the way of (no attempts)
    int64_t failed_utime = 0;       // the last failure ...
    PlaceView view_at_failure;      // ... and the map around the place then ...
    std::optional<LastFailure> failed_from;   // ... and where the robot stood, on which map
  };
  std::vector<FailedPlace> failed_;             // frontier goals the planner could not reach
  std::optional<LastFailure> last_failure_;     // of any goal: where the robot stood, on which map
  bool arrived_since_failure_ = false;          // the robot arrived at a goal since the last counted "no progress"
  std::vector<Eigen::Vector2d> track_;          // map frame: where the robot was, newest last
  Recovery recovery_due_ = Recovery::kNone;
  std::optional<Eigen::Vector2d> looked_at_, stepped_from_;   // where the last look / step began
  std::set<int64_t> finished_regions_, offered_regions_;
  int64_t last_region_ = 0;
  int goals_sent_ = 0, goals_reached_ = 0, goals_failed_ = 0;
  std::string activity_;
  std::string last_end_;
};

}  // namespace rgnav::explorer
