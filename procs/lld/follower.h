// The low-level drive's trajectory follower: one call per control period turns the newest
// odometry and the active plan into a velocity command and a status. It follows the chain's
// velocity profile in time (so traversal times are what the profile predicts), switches
// segments by following the profile across joints, takes a new plan at any time starting
// from the current command (the slew limits keep the commanded velocities continuous), and
// stops within the drive's limits when its inputs go stale.
//
// step() never allocates: plans are prepared (chain, profile) outside the control loop and
// handed over whole; the follower only reads them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "lld/tracking_law.h"
#include "time/message_time.h"
#include "trajectory/trajectory.h"
#include "trajectory/velocity_profile.h"

namespace rgnav::lld {

using geometry::Pose2;

struct FollowerOptions
{
  TrackingGains gains;
  trajectory::Limits limits;        // the drive's limits; a trajectory may only lower a_max, omega_max
  // Velocity profiles use this fraction of v_max and a_max: the rest is the feedback's
  // authority to catch up (a profile at the drive's limits leaves the controller none).
  double profile_fraction = 0.85;
  double stop_decel = 0.5;          // [m/s^2] controlled stops (stale input, end of plan)
  double wait_error_start = 0.10;   // [m] along-track lag at which the reference starts to wait
  double wait_error_full = 0.30;    // [m] lag at which it stops advancing
  double odometry_timeout = 0.25;   // [s] older odometry: controlled stop
  double trajectory_timeout = 1.5;  // [s] a plan not refreshed this long while moving: stop
  double profile_ds = 0.02;         // [m] velocity profile sample spacing
  // The feed-forward (v_r, omega_r) is taken this far ahead on the profile: a command acts
  // over the coming period and through the drive's response lag, not at the instant it is sent.
  double feedforward_lead = 0.05;   // [s]
  double end_tolerance = 0.02;      // [m] along-track error at which the end is reached
  double end_settle_timeout = 2.0;  // [s] after the reference arrived, stop anyway
  // Measured below both: the robot stands (a stop does not move it again, Follower::step).
  double rest_speed = 0.005;        // [m/s]
  double rest_omega = 0.01;         // [rad/s]
};

// A trajectory ready to follow: chain and its velocity profile (computed off the loop).
struct Plan
{
  trajectory::Trajectory trajectory;
  trajectory::VelocityProfile profile;
  trajectory::Limits limits;  // the limits the profile respects
};

// Builds the plan for t, starting at speed v_start (the current command).
std::unique_ptr<Plan> make_plan(trajectory::Trajectory t, const FollowerOptions& options, double v_start);

struct OdometryInput
{
  Pose2 pose;              // odom_from_base
  double v = 0.0;
  double omega = 0.0;
  time::Time stamp{};
};

enum class FollowerState : int8_t
{
  kIdle = 0,
  kTracking = 1,
  kDone = 2,
  kStopping = 3,
  kFault = 4,
};

enum class StopReason : int8_t
{
  kNone = 0,
  kStaleOdometry,
  kStaleTrajectory,
  kCancelled,
  kEndOfPlan,
  kLoopGap,  // the control loop itself was held up past its bounds (halt())
};

struct FollowerStatus
{
  FollowerState state = FollowerState::kIdle;
  StopReason stop_reason = StopReason::kNone;
  int64_t trajectory_id = 0;
  int32_t segment = 0;
  double progress = 0.0;        // [m] along the chain (closest point)
  double cross_track = 0.0;     // [m] left of the path positive
  double heading_error = 0.0;   // [rad] path heading minus robot heading
  double reference_s = 0.0;     // [m] where the reference is
  VelocityCommand command;
  time::Time predicted_end{};
};

class Follower
{
 public:
  explicit Follower(const FollowerOptions& options) : options_(options) {}

  // Makes plan the active one from the next step on; returns the previous plan (the caller
  // frees it, outside the control loop). A plan with an empty chain cancels: controlled stop.
  std::unique_ptr<Plan> replace(std::unique_ptr<Plan> plan, time::Time received);
  // The sender re-sent the active trajectory unchanged: it is still wanted.
  void refresh(int64_t trajectory_id, time::Time received);

  // One control period: `now` in message time, dt the period just elapsed [s].
  const FollowerStatus& step(time::Time now, double dt, const OdometryInput* odometry);
  // Instead of step() after the control loop was held up longer than the base follows one
  // command (the process was stopped and continued, or the host stalled): the command last
  // computed and the inputs found on waking (queued during the gap) describe a past that is
  // gone, and anything tracked from them (the reference ran on by the gap) is a stale moving
  // command. Commands zero at once (no ramp: the base's own deadman has been stopping the robot
  // since the commands ceased) and stays idle until a plan stamped after `now` arrives, so
  // trajectories queued during the gap are not taken up either.
  const FollowerStatus& halt(time::Time now);

  const FollowerStatus& status() const { return status_; }
  VelocityCommand last_command() const { return status_.command; }
  const Plan* plan() const { return plan_.get(); }

 private:
  VelocityCommand track(const OdometryInput& odo, double dt, time::Time now);
  VelocityCommand slew(const VelocityCommand& want, double dt, double decel) const;
  void stop(StopReason why) { status_.state = FollowerState::kStopping; status_.stop_reason = why; }

  const FollowerOptions options_;
  std::unique_ptr<Plan> plan_;
  bool adopt_pending_ = false;
  time::Time plan_refreshed_{};
  double tau_ = 0.0;  // [s] reference time along the active profile
  double settle_ = 0.0;  // [s] time spent at the end waiting to arrive
  std::optional<time::Time> halted_at_;  // the last halt(): plans stamped up to it are not adopted
  FollowerStatus status_;
};

}  // namespace rgnav::lld
