#include "base_driver/synchro_drive_controller.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace rgnav::can::base {

using master::DriveState;
using PowerState = canopen::cia402::PowerState;

const char* to_string(BaseStatus s)
{
  switch (s) {
    case BaseStatus::kOk: return "ok";
    case BaseStatus::kStopped: return "stopped";
    case BaseStatus::kFault: return "fault";
  }
  return "?";
}

namespace {

double ramp(double current, double target, double max_step)
{
  return current + std::clamp(target - current, -max_step, max_step);
}

}  // namespace

SynchroDriveController::SynchroDriveController(const BaseDriverOptions& options, Sink send)
    : options_(options),
      master_(options.master, std::move(send)),
      translation_(&master_.add_drive(options.translation.drive_options(options.drive_common))),
      rotation_(&master_.add_drive(options.rotation.drive_options(options.drive_common))),
      odometry_(options.translation.counts_per_unit, options.translation.sign, options.rotation.counts_per_unit,
                options.rotation.sign)
{
}

void SynchroDriveController::command(const VelocityCommand& cmd, Clock::time_point received, Clock::duration deadline)
{
  command_ = cmd;
  command_expires_ = received + std::min<Clock::duration>(deadline, options_.command_deadline);
}

void SynchroDriveController::handle(const can_frame& f, Clock::time_point now) { master_.handle(f, now); }

void SynchroDriveController::quick_stop(bool hold, const std::string& why)
{
  if (hold && !safety_stop_) spdlog::warn("quick stop: {}", why);
  if (hold) {
    safety_stop_ = true;
    safety_stop_why_ = why;
    reenable_until_.reset();
  }
  release_pending_ = !hold && safety_stop_;
}

void SynchroDriveController::release_quick_stop(Clock::time_point now)
{
  // Not while a drive still ramps down: leaving Quick stop active early disables its power
  // stage (transition 12), and a motor without power runs free.
  const auto ramping = [](const master::DriveMaster* d) { return d->power_state() == PowerState::kQuickStopActive; };
  if (!release_pending_ || ramping(translation_) || ramping(rotation_)) return;
  safety_stop_ = false;
  release_pending_ = false;
  // From quick stop the drives end in switch on disabled: walking them up again takes a few
  // SYNC cycles, which is not a drive dropping out.
  reenable_until_ = now + options_.drive_common.enable_timeout;
  spdlog::info("quick stop released: re-enabling the drives");
}

std::string SynchroDriveController::fault_reason() const
{
  if (master_.bus_off()) return "CAN bus-off";
  std::string r;
  for (const auto* d : {translation_, rotation_}) {
    if (d->enabled()) continue;
    if (!r.empty()) r += "; ";
    r += (d == translation_ ? "translation drive " : "rotation drive ") + std::to_string(d->node_id()) + ": " +
         d->reason();
  }
  return r;
}

bool SynchroDriveController::at_standstill() const
{
  return translation_->velocity() == 0 && rotation_->velocity() == 0;
}

void SynchroDriveController::tick(Clock::time_point now)
{
  const double dt = last_tick_ ? std::chrono::duration<double>(now - *last_tick_).count() : 0.0;
  last_tick_ = now;

  release_quick_stop(now);
  const bool all_enabled = translation_->enabled() && rotation_->enabled();
  if (all_enabled && !ever_enabled_) spdlog::info("both drives in operation enabled");
  ever_enabled_ = ever_enabled_ || all_enabled;
  if (all_enabled || (reenable_until_ && now > *reenable_until_)) reenable_until_.reset();
  const auto hard_fault = [](const master::DriveMaster* d) {
    return d->state() == DriveState::kFault || d->state() == DriveState::kLost;
  };
  // After the first full enable, any drive dropping out is a fault (it was running), unless a
  // safety stop took them out on purpose.
  const bool deliberately_out = safety_stop_ || reenable_until_.has_value();
  const bool fault = master_.bus_off() || hard_fault(translation_) || hard_fault(rotation_) ||
                     (ever_enabled_ && !all_enabled && !deliberately_out);
  const bool fresh = command_ && now <= command_expires_;

  // Fault: hold whatever is still reachable in quick stop. Released only once no drive is in
  // fault or lost, so a recovered drive does not start moving while the other is broken.
  const bool hold = master_.bus_off() || hard_fault(translation_) || hard_fault(rotation_) || safety_stop_;
  translation_->set_quick_stop(hold);
  rotation_->set_quick_stop(hold);

  if (all_enabled && fresh && !released_ && !safety_stop_) {
    const VelocityCommand& c = *command_;
    const double v = std::clamp(c.v, -options_.translation.max_velocity, options_.translation.max_velocity);
    const double w = std::clamp(c.omega, -options_.rotation.max_velocity, options_.rotation.max_velocity);
    ramped_.v = ramp(ramped_.v, v, options_.translation.max_acceleration * dt);
    ramped_.omega = ramp(ramped_.omega, w, options_.rotation.max_acceleration * dt);
  } else {
    // Controlled stop: target 0, the drives decelerate on their profile ramps (0x6084).
    ramped_ = {};
  }
  translation_->set_target_velocity(options_.translation.to_counts(ramped_.v));
  rotation_->set_target_velocity(options_.rotation.to_counts(ramped_.omega));

  master_.tick(now);
  integrate_odometry();

  odom_.commanded = ramped_;
  if (fault) {
    odom_.status = BaseStatus::kFault;
    odom_.reason = fault_reason();
  } else if (safety_stop_) {
    odom_.status = BaseStatus::kStopped;
    odom_.reason = "quick stop: " + safety_stop_why_;
  } else if (!all_enabled && reenable_until_) {
    odom_.status = BaseStatus::kStopped;
    odom_.reason = "re-enabling after a quick stop";
  } else if (!all_enabled) {
    odom_.status = BaseStatus::kStopped;
    odom_.reason = "bringing drives up: " + fault_reason();
  } else if (!fresh || released_) {
    odom_.status = BaseStatus::kStopped;
    odom_.reason = command_ ? "command stale (deadman)" : "no command yet";
  } else {
    odom_.status = BaseStatus::kOk;
    odom_.reason.clear();
  }
}

void SynchroDriveController::integrate_odometry()
{
  // A reconfigured drive may have rebooted: its counter restarts somewhere else.
  if (translation_->position_epoch() != epoch_t_ || rotation_->position_epoch() != epoch_r_) {
    epoch_t_ = translation_->position_epoch();
    epoch_r_ = rotation_->position_epoch();
    odometry_.rebaseline();
  }
  // One step per SYNC cycle, once both drives have reported their position for it.
  if (translation_->position_samples() == used_samples_t_ || rotation_->position_samples() == used_samples_r_) return;
  used_samples_t_ = translation_->position_samples();
  used_samples_r_ = rotation_->position_samples();
  odometry_.update(translation_->position(), rotation_->position());
  odom_.pose = odometry_.pose();
  odom_.distance = odometry_.distance();
  odom_.v = options_.translation.to_units(translation_->velocity());
  odom_.omega = options_.rotation.to_units(rotation_->velocity());
  ++odom_.samples;
}

}  // namespace rgnav::can::base
