// Trajectory-based collision avoidance (diss. 5.5.3): given the next targets (0.5-2 m apart,
// odom frame), the odometry pose and the sensor data, it builds chains of primitives to the
// next targets, checks them against the local map with the footprint and a margin, hands
// them to the low-level drive, watches the drive's progress and replans in time when an
// obstacle appears on the planned chain. When none of the chain planner's candidates is
// free it looks for a detour on the grid (grid_path.h) and builds primitives along it, then
// for a chain or detour through a passage narrower than the full clearance, with a smaller
// margin, slowly (squeeze_margin); when that fails too it falls back to Holz et al.'s reactive
// behaviours (wait, back off from what is too close, back along its own track out of a tight
// place it drove into (own_track.h), turn or steer toward free space), expressed as short
// trajectories too (the drive stays the only one commanding the base). A person in its way in
// a doorway or a narrow hallway, whose way the robot blocks in turn, gets it out of their way
// sideways until they have passed (give_way.h, yielding.cpp). Stale scans: stop. Runs on
// message time; knows no LCM.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "collision_avoidance/chain_planner.h"
#include "collision_avoidance/give_way.h"
#include "collision_avoidance/grid_path.h"
#include "collision_avoidance/local_map.h"
#include "collision_avoidance/own_track.h"
#include "collision_avoidance/reactive.h"
#include "trajectory/trajectory.h"

namespace rgnav::collision_avoidance {

struct CaOptions
{
  LocalMapOptions map;
  PlannerOptions planner;
  ReactiveOptions reactive;
  GridPathOptions grid;            // detours when no chain candidate is free
  double detour_speed = 0.35;      // [m/s] along grid detours
  // A passage narrower than the full clearance (radius + safety margin) that the body fits
  // through with squeeze_margin, as the route may lead (the route planner keeps its margin
  // only where the passage allows): a chain or detour with that margin instead, at
  // squeeze_speed. Without it the robot stood at such a passage's mouth for good (the reactive
  // fallback, steering with half the margin, brought it there). 0: off.
  // Optionally not begun with a person within squeeze_people (walking, or walked up and
  // stopped; 0: off): a person standing still keeps only the plain margin. In the doorway
  // encounters (60) one person stepping round the robot passed it at 1 cm instead of 12 with the
  // squeeze; 1.5 m kept 12 cm but cost exploring a furnished building rooms (control bench and
  // explore bench, one run each): off until measured on more.
  double squeeze_margin = 0.0;     // [m] (config/collision_avoidance.yaml says why it is off)
  double squeeze_speed = 0.2;      // [m/s]
  double squeeze_people = 0.0;     // [m]
  Pose2 base_from_laser{0.12, 0.0, 0.0};
  double reach_radius = 0.35;      // [m] an intermediate target counts as passed this close
  double goal_tolerance = 0.10;    // [m] the final goal
  int lookahead_targets = 2;       // targets one chain reaches
  // [m] Targets are local (the route planner sends the next few metres): one farther from the
  // robot is no target to plan a chain to (a corrupted list, a frame mixed up) and stops the
  // robot; a chain to a target 9 km away took seconds to sample, and the lld refuses its segments.
  double max_target_distance = 20.0;
  double scan_timeout = 0.5;       // [s] no scan this long: stop
  double update_period = 0.1;      // [s] decisions at most this often (message time)
  double refresh_period = 0.5;     // [s] re-send the active trajectory (keep-alive for the lld)
  double resend_tolerance = 0.15;  // [m] targets of the same goal re-sent within this are no new targets
  double replan_cross_track = 0.2; // [m] the drive is this far off the chain: replan
  double fallback_wait = 1.5;      // [s] blocked: stand this long (people pass) before turning away
  double backoff_length = 0.4;     // [m] too close to something: drive away this far
  double backoff_speed = 0.15;     // [m/s]
  double headway = 0.3;            // [m] moving this far counts as headway ...
  double yield_after = 8.0;        // [s] ... none for this long: back away (yield) ...
  double yield_reach = 0.5;        // [m] ... from what is this much farther than the clearance
  GiveWayOptions give_way;         // ... by driving back, away from the target (give_way.h)
  // ... or, before backing away from what is near, leave the way it came (own_track.h): a
  // place it drove into with less than the full clearance keeps it there by every other rule.
  bool retrace_own_track = true;
  OwnTrackOptions own_track;
  double retrace_speed = 0.15;     // [m/s]
  double give_way_speed = 0.25;    // [m/s]
  double give_way_timeout = 20.0;  // [s] giving way ends after this even if not done
  // A person in the way (walking toward the robot with it on their path, within yield_notice,
  // or stopped there) and no headway for yield_sideways_after: leave their path sideways
  // (give_way.yield) at yield_speed, wait there until nobody is left to pass for pass_settle,
  // or yield_wait_timeout; the whole of it ends after yield_timeout.
  double yield_sideways_after = 2.0;  // [s]
  double yield_head_on_after = 0.5;   // [s] someone coming straight down the robot's way
  double yield_notice = 4.0;          // [m] walking toward the robot
  double yield_notice_stopped = 2.0;  // [m] stopped in front of it
  double yield_speed = 0.45;          // [m/s]
  double pass_settle = 1.5;           // [s]
  // Only someone standing on the path for standing_go_after, waiting for the robot in turn, and
  // a chain past them to the targets free: go on (two parties waiting for each other).
  double standing_go_after = 4.0;     // [s]
  double yield_wait_timeout = 25.0;   // [s]
  double yield_timeout = 60.0;        // [s]
  double a_max = 0.4;              // [m/s^2] sent with every trajectory
  double omega_max = 1.0;          // [rad/s]
};

struct Targets
{
  int64_t goal_id = 0;
  std::vector<Pose2> poses;  // odom frame, driving order
  double max_speed = 0.5;
  bool final_is_goal = true;
};

struct DriveFeedback
{
  int64_t trajectory_id = 0;
  int state = 0;           // lld_status_t::STATE_* values (0 idle, 1 tracking, 2 done, 3 stopping)
  double progress = 0.0;   // [m]
  double cross_track = 0.0;
  double v_cmd = 0.0;
};

enum class Mode
{
  kIdle,        // no targets
  kPlanned,     // following a planned chain
  kReactive,    // fallback behaviours
  kBlocked,     // stopped: nothing feasible, not even turning
  kStaleStop,   // stopped: scans stale
  kArrived,     // final goal reached
  kYielding,    // out of a person's way by choice: leaving their path, waiting for them to pass, going back
};

const char* mode_name(Mode m);

class CollisionAvoidance
{
 public:
  explicit CollisionAvoidance(const CaOptions& options);

  void set_targets(const Targets& targets);
  void cancel();
  void on_odometry(time::Time stamp, const Pose2& odom_from_base, double v);
  // Scan readings in the laser frame as (bearing, range); range >= range_max means no return.
  // Placed with the odometry pose at the scan's stamp, between the two odometry messages around
  // it (odometry newer than the scan may have come first: scans at 75 Hz, odometry at 50 Hz);
  // without both, with the newest pose.
  void on_scan(time::Time stamp, const std::vector<PolarReading>& laser_readings, double range_max);
  void on_obstacle_points(time::Time stamp, std::vector<Eigen::Vector2d> odom_points);
  void on_drive_feedback(const DriveFeedback& feedback) { feedback_ = feedback; has_feedback_ = true; }

  // Decides at message time `now`: a trajectory to send (new, or the active one re-sent).
  std::optional<trajectory::Trajectory> update(time::Time now);

  Mode mode() const { return mode_; }
  const std::string& status() const { return status_; }
  size_t next_target() const { return next_; }
  const LocalMap& map() const { return map_; }
  const std::optional<trajectory::Trajectory>& active() const { return active_; }
  int64_t replans() const { return replans_; }
  int64_t fallbacks() const { return fallbacks_; }
  int64_t detours() const { return detours_; }
  int64_t yields() const { return yields_; }  // times it began to leave a person's path sideways

 private:
  std::optional<trajectory::Trajectory> send_new(trajectory::Chain chain, time::Time now, double predicted, Mode mode);
  std::optional<trajectory::Trajectory> stop(time::Time now, Mode mode, const std::string& why);
  std::optional<trajectory::Trajectory> reactive(time::Time now);
  // Backs away from obstacle points closer than `radius` (none: nullopt).
  std::optional<trajectory::Trajectory> backing_off(time::Time now, double radius);
  // No headway: drive back up to `length`, away from the target, out of the way of whoever
  // waits (none free: nullopt; moving and needing a turn: a stop first).
  std::optional<trajectory::Trajectory> giving_way(time::Time now, double length);
  // No headway: back along the robot's own track with the clearance it had there (own_track.h),
  // turning on the spot at its corners (none: nullopt; moving: a stop first).
  std::optional<trajectory::Trajectory> retracing(time::Time now);
  // Something now on what remains of the way back, closer than the robot was there.
  bool retrace_blocked() const;
  // A person who walked up and stopped stands within `reach` (people_tracker.h LastSeenMover).
  bool someone_waits_near(double reach) const;
  // A tracked person (walking, or walked up and stopped) within `reach`.
  bool person_within(double reach) const;
  // A squeeze may go on (the body keeps `tight`) or begin (the robot has the full `clearance`,
  // nobody within squeeze_people).
  bool may_squeeze(double clearance, double tight) const;
  bool targets_changed_goal() const { return targets_.goal_id != give_way_goal_id_; }
  // Leaving a person's path sideways (yielding.cpp). The person in the way, if any: someone
  // walking toward the robot with it on their path, or someone who stopped in front of it.
  struct PersonInTheWay
  {
    PersonPath path;
    bool walking = false;  // walking now (else: walked up and stopped)
    Eigen::Vector2d at = Eigen::Vector2d::Zero();  // where they are (odom frame)
    double speed = 0.0;    // [m/s] walking (0: stopped)
  };
  std::optional<PersonInTheWay> person_in_the_way() const;
  // Before either is in it: someone walking toward the robot, with a stretch between them too
  // narrow to pass each other (one_lane_between) that they would enter before the robot is
  // out of it (or they are in it already). The robot does not go in: it leaves their path now
  // (start_yield): what to send (maybe nothing). nullopt: no reason, or not for
  // yield_head_on_after yet; decide normally.
  std::optional<std::optional<trajectory::Trajectory>> yield_before_one_lane(time::Time now);
  // [s] a yield manoeuvre takes the drive.
  double manoeuvre_time(const trajectory::Chain& c) const;
  // Where the robot's way leads (unit, odom frame): toward its first target at least a metre off.
  std::optional<Eigen::Vector2d> way_ahead() const;
  std::optional<trajectory::Trajectory> start_yield(time::Time now, const PersonPath& path);
  // From where the robot is: to the yield point (or a look behind first, or waiting where it is).
  // Nothing: the yield ended (no place to go).
  std::optional<trajectory::Trajectory> leave_path(time::Time now);
  // The yield under way: what to send (maybe nothing); nullopt: it ended, decide normally.
  std::optional<std::optional<trajectory::Trajectory>> yield_under_way(time::Time now);
  // `done`: it ran its course (the headway clock starts again); otherwise it found no way out
  // of the person's path, and the older fallbacks get their turn before the next try.
  void end_yield(time::Time now, bool done);
  // Back to where the yield began (nothing: near it already, or no free way there).
  std::optional<trajectory::Trajectory> return_to_way(time::Time now);
  // Something there now on what remains of the yield's manoeuvre (first_collision's rule on the
  // observed points: where a mover is only predicted to walk does not count).
  bool yield_way_blocked() const;
  // A reactive turn on the spot, sent now, runs to its end (kept alive for the lld) unless a
  // chain to the targets turns up first.
  std::optional<trajectory::Trajectory> send_reactive_turn(double angle, time::Time now, const std::string& why);
  // The reactive turn under way (nullopt: none, or it ended); a keep-alive when one is due.
  std::optional<std::optional<trajectory::Trajectory>> reactive_turn_under_way(time::Time now);
  std::optional<trajectory::Trajectory> commit_backoff(std::optional<trajectory::Trajectory> t, time::Time now,
                                                       double duration);
  std::vector<Pose2> goals() const;
  // One of `aims` lies farther from the robot than max_target_distance: no local target.
  bool beyond_reach(const std::vector<Pose2>& aims) const;
  bool advance_targets();

  const CaOptions options_;
  const ChainPlanner planner_;
  const ChainPlanner squeeze_planner_;  // the same with squeeze_margin
  bool squeezing_ = false;              // the active chain keeps only squeeze_margin
  LocalMap map_;
  Targets targets_;
  bool has_targets_ = false;
  bool targets_changed_ = false;
  std::vector<Pose2> changed_to_;  // the targets when they last counted as changed
  size_t next_ = 0;
  bool has_pose_ = false;
  Pose2 pose_;
  // The odometry of the last kOdometryKept seconds, for the pose at a scan's stamp. Placed with
  // the newest pose instead, the scans of a turn on the spot put the walls a few degrees off
  // from scan to scan (centimetres to decimetres away): wall pieces that moved, tracked as
  // people walking (a robot yielding to one at a hallway's mouth, nobody there).
  struct OdometrySample
  {
    int64_t utime = 0;
    Pose2 pose;
  };
  std::deque<OdometrySample> odometry_;
  Pose2 pose_at(time::Time stamp) const;
  double v_ = 0.0;
  time::Time last_scan_{};
  bool has_scan_ = false;
  std::vector<PolarReading> last_readings_;  // base frame
  DriveFeedback feedback_;
  bool has_feedback_ = false;
  std::optional<trajectory::Trajectory> active_;
  time::Time last_sent_{};
  time::Time last_update_{};
  bool updated_once_ = false;
  bool stopped_ = false;  // the last thing sent was a stop
  int64_t next_id_ = 1;
  int64_t replans_ = 0;
  int64_t fallbacks_ = 0;
  int64_t detours_ = 0;
  int64_t yields_ = 0;
  std::optional<int64_t> backoff_id_;  // the back-off manoeuvre under way, run to its end
  int64_t backoff_goal_id_ = 0;        // ... unless the goal changes
  bool giving_way_now_ = false;        // the manoeuvre under way gives way
  OwnTrack track_;                     // where the robot drove (not while driving back over it)
  struct RetracePoint
  {
    Eigen::Vector2d at;
    double need = 0.0;  // [m] clearance it needs there now
  };
  std::vector<RetracePoint> retrace_;  // the way back under way (empty: none)
  bool give_way_active_ = false;       // giving way until this far from where it began, or until ...
  Eigen::Vector2d give_way_from_ = Eigen::Vector2d::Zero();
  time::Time give_way_until_{};        // ... this time
  int64_t give_way_goal_id_ = 0;
  bool has_yield_anchor_ = false;      // where the robot got stuck, for give_way_timeout
  Eigen::Vector2d yield_anchor_ = Eigen::Vector2d::Zero();
  time::Time yield_anchor_time_{};
  time::Time backoff_until_{};
  bool has_progress_pose_ = false;
  Eigen::Vector2d progress_pose_ = Eigen::Vector2d::Zero();
  time::Time progress_since_{};
  std::optional<int64_t> reactive_turn_id_;  // the reactive turn under way ...
  time::Time reactive_turn_until_{};         // ... and when it should have ended
  bool blocked_since_set_ = false;
  time::Time blocked_since_{};
  enum class YieldPhase
  {
    kNone,
    kLooking,  // turning on the spot: nothing known behind the robot, where the way out may be
    kLeaving,  // on the way to the yield point
    kWaiting,  // there, until nobody is left to pass
    kReturning,  // back the way it came, to where it left its way
  };
  struct Yield
  {
    YieldPhase phase = YieldPhase::kNone;
    PersonPath path;
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
    int64_t goal_id = 0;
    Eigen::Vector2d goal_at = Eigen::Vector2d::Zero();  // the last target when it began
    time::Time since{};        // the phase began
    time::Time phase_until{};  // the phase's manoeuvre should have ended by then
    time::Time until{};        // the whole yield ends then
    bool clear = false;        // waiting: nobody to pass since clear_since
    time::Time clear_since{};
    bool standing = false;     // waiting: only someone standing since standing_since
    time::Time standing_since{};
    int64_t trajectory_id = 0;  // the manoeuvre under way (0: none yet, stopping first)
    bool looked = false;
    int plans = 0;             // yield points chosen (blocked ways re-plan, a few times)
    int returns = 0;           // ways back chosen anew
    time::Time rechecked{};    // leaving: last looked for a nearer place
    std::vector<Eigen::Vector2d> trail;  // where the robot drove since it began (odom frame, 0.1 m apart; the first: where it left its way)
    double start_heading = 0.0;          // [rad] its heading on its way when it began
  };
  Yield yield_;
  time::Time yield_retry_after_{};  // no new yield before (after one that found no way out)
  bool one_lane_meeting_ = false;   // yield_before_one_lane's reason holds since ...
  time::Time one_lane_since_{};
  Mode mode_ = Mode::kIdle;
  std::string status_ = "idle";
};

}  // namespace rgnav::collision_avoidance
