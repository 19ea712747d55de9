#include "lld/follower.h"

#include <algorithm>
#include <cmath>

namespace rgnav::lld {

using trajectory::Kind;

std::unique_ptr<Plan> make_plan(trajectory::Trajectory t, const FollowerOptions& options, double v_start)
{
  auto plan = std::make_unique<Plan>();
  plan->limits = options.limits;
  plan->limits.v_max = options.profile_fraction * options.limits.v_max;
  plan->limits.a_max = std::min(options.profile_fraction * options.limits.a_max, t.a_max);
  plan->limits.omega_max = std::min(options.profile_fraction * options.limits.omega_max, t.omega_max);
  plan->limits.alpha_max = options.profile_fraction * options.limits.alpha_max;
  plan->trajectory = std::move(t);
  plan->profile = trajectory::VelocityProfile::compute(plan->trajectory.chain, plan->limits, std::max(0.0, v_start),
                                                       0.0, options.profile_ds);
  return plan;
}

std::unique_ptr<Plan> Follower::replace(std::unique_ptr<Plan> plan, time::Time received)
{
  std::swap(plan_, plan);
  adopt_pending_ = true;
  plan_refreshed_ = received;
  return plan;
}

void Follower::refresh(int64_t trajectory_id, time::Time received)
{
  if (plan_ && plan_->trajectory.id == trajectory_id) plan_refreshed_ = received;
}

VelocityCommand Follower::slew(const VelocityCommand& want, double dt, double decel) const
{
  const auto& lim = options_.limits;  // the drive's: the profile left headroom below them
  const VelocityCommand& prev = status_.command;
  VelocityCommand out;
  const double v = std::clamp(want.v, 0.0, lim.v_max);
  // Speeding up at the trajectory's a_max; braking at least as hard as `decel` allows.
  const double up = lim.a_max * dt, down = std::max(decel, lim.a_max) * dt;
  out.v = std::clamp(v, prev.v - down, prev.v + up);
  const double w = std::clamp(want.omega, -lim.omega_max, lim.omega_max);
  const double dw = lim.alpha_max * dt;
  out.omega = std::clamp(w, prev.omega - dw, prev.omega + dw);
  return out;
}

const FollowerStatus& Follower::step(time::Time now, double dt, const OdometryInput* odo)
{
  const bool odometry_fresh =
      odo && time::to_seconds(now - odo->stamp) <= options_.odometry_timeout && time::to_seconds(now - odo->stamp) >= -1.0;

  if (adopt_pending_ && plan_ && halted_at_ && plan_->trajectory.stamp <= *halted_at_) adopt_pending_ = false;  // queued in a gap
  if (adopt_pending_) {
    adopt_pending_ = false;
    status_.stop_reason = StopReason::kNone;
    if (!plan_ || plan_->trajectory.chain.empty()) {
      if (status_.state == FollowerState::kTracking || status_.command.v != 0 || status_.command.omega != 0)
        stop(StopReason::kCancelled);
      status_.trajectory_id = plan_ ? plan_->trajectory.id : 0;
    } else {
      // Start where the robot is along the new chain (it was planned from a slightly older pose).
      tau_ = 0.0;
      settle_ = 0.0;
      if (odo) {
        const auto pr = plan_->trajectory.chain.project(odo->pose.translation(), 0.0, 1.0);
        if (pr.local.distance < 0.5) tau_ = plan_->profile.time_at(pr.s);
      }
      status_.state = FollowerState::kTracking;
      status_.trajectory_id = plan_->trajectory.id;
    }
  }

  VelocityCommand want;
  double decel = options_.stop_decel;
  if (status_.state == FollowerState::kTracking) {
    if (!odometry_fresh) {
      stop(StopReason::kStaleOdometry);
    } else if (time::to_seconds(now - plan_refreshed_) > options_.trajectory_timeout) {
      stop(StopReason::kStaleTrajectory);
    }
  }
  if (status_.state == FollowerState::kTracking) {
    want = track(*odo, dt, now);
    decel = options_.limits.a_max;
  } else if (odometry_fresh && plan_ && !plan_->trajectory.chain.empty() && status_.state == FollowerState::kStopping &&
             status_.stop_reason == StopReason::kStaleTrajectory) {
    // Still measured: keep steering along the path while braking.
    want = track(*odo, dt, now);
    want.v = 0.0;
  }
  status_.command = slew(want, dt, decel);
  // A stop ramps the command down from the last command, not from what the robot does. A base
  // that stopped the robot itself meanwhile (a drive fault, its deadman in a host stall, with
  // the odometry stale) would, once back, drive the rest of that ramp: a robot measured at rest
  // during a stop is held at rest.
  if (status_.state == FollowerState::kStopping && odometry_fresh && std::fabs(odo->v) < options_.rest_speed &&
      std::fabs(odo->omega) < options_.rest_omega)
    status_.command = {};
  if (status_.state == FollowerState::kStopping && status_.command.v == 0.0 && status_.command.omega == 0.0)
    status_.state = status_.stop_reason == StopReason::kEndOfPlan ? FollowerState::kDone : FollowerState::kIdle;
  if (status_.state == FollowerState::kTracking && !plan_) status_.state = FollowerState::kIdle;
  return status_;
}

const FollowerStatus& Follower::halt(time::Time now)
{
  status_.command = {};
  status_.state = FollowerState::kIdle;
  status_.stop_reason = StopReason::kLoopGap;
  adopt_pending_ = false;
  halted_at_ = now;
  return status_;
}

VelocityCommand Follower::track(const OdometryInput& odo, double dt, time::Time now)
{
  const auto& chain = plan_->trajectory.chain;
  const auto& profile = plan_->profile;
  const double total = profile.total_time();
  const trajectory::ProfileState ref = profile.at_time(tau_);
  const trajectory::ProfileState ahead = profile.at_time(tau_ + options_.feedforward_lead);

  Pose2 ref_pose;
  double v_r = ref.v, omega_r = 0.0;
  size_t segment;
  if (ref.turn >= 0) {
    segment = static_cast<size_t>(ref.turn);
    const Pose2& st = chain[segment].start();
    ref_pose = Pose2(st.translation(), st.theta() + ref.turn_angle);
    v_r = 0.0;
    omega_r = ahead.turn == ref.turn ? ahead.omega_turn : ref.omega_turn;
  } else {
    segment = chain.segment_at(ref.s);
    ref_pose = chain.pose_at(ref.s);
    v_r = ahead.turn < 0 ? ahead.v : 0.0;
    omega_r = ahead.turn < 0 ? chain.curvature_at(ahead.s) * v_r : 0.0;
  }

  const TrackingError e = tracking_error(ref_pose, odo.pose);
  VelocityCommand want = kanayama(e, v_r, omega_r, options_.gains);
  if (ref.turn >= 0) want.omega += options_.gains.k_turn * std::sin(e.e_theta);

  // Path-relative errors for the status (closest point near the reference).
  const auto pr = chain.project(odo.pose.translation(), std::max(0.0, ref.s - 1.0), ref.s + 1.0);
  status_.segment = static_cast<int32_t>(ref.turn >= 0 ? segment : pr.segment);
  status_.progress = pr.s;
  status_.cross_track = pr.local.lateral;
  status_.heading_error =
      geometry::normalize_angle((ref.turn >= 0 ? ref_pose.theta() : pr.local.pose.theta()) - odo.pose.theta());
  status_.reference_s = ref.s;

  // The reference waits when the robot lags far behind it (blocked, saturated), so the
  // controller never has to catch up a large gap at once.
  const double lag = e.e_x;
  const double rate = std::clamp(1.0 - (lag - options_.wait_error_start) /
                                           (options_.wait_error_full - options_.wait_error_start),
                                 0.0, 1.0);
  tau_ = std::min(total, tau_ + dt * rate);
  status_.predicted_end = now + time::Duration(static_cast<int64_t>((total - tau_) * 1e6));

  if (tau_ >= total) {
    // The reference has arrived. Stopping at the end: close the remaining along-track gap
    // (v = k_x e_x), then stop. More was expected (no stop at the end): brake on the spot.
    settle_ += dt;
    if (!plan_->trajectory.stop_at_end || std::fabs(e.e_x) < options_.end_tolerance ||
        settle_ > options_.end_settle_timeout) {
      stop(StopReason::kEndOfPlan);
      want.v = 0.0;
    }
  }
  return want;
}

}  // namespace rgnav::lld
