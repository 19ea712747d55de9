#include "sim/protocol_drives.h"

namespace rgnav::sim {

namespace {

using can::emulator::DriveEmulator;
using can::emulator::DriveEmulatorOptions;
using PowerState = DriveEmulator::PowerState;

DriveEmulatorOptions emulator_options(const can::base::AxisOptions& axis)
{
  DriveEmulatorOptions o;
  o.node_id = axis.node_id;
  return o;
}

// The power stage is on (the motor is driven, possibly braking in a quick stop).
bool powered_stage(const DriveEmulator& d)
{
  const PowerState s = d.power_state();
  return d.powered() &&
         (s == PowerState::kOperationEnabled || s == PowerState::kQuickStopActive || s == PowerState::kFaultReactionActive);
}

}  // namespace

ProtocolDrives::ProtocolDrives(const DriveAxes& axes, Sink translation_out, Sink rotation_out)
    : axes_(axes),
      translation_(emulator_options(axes.translation), std::move(translation_out)),
      rotation_(emulator_options(axes.rotation), std::move(rotation_out))
{
  translation_.attach_physics(true);
  rotation_.attach_physics(true);
}

void ProtocolDrives::power_on(int64_t utime)
{
  translation_.power_on(emulator_time(utime));
  rotation_.power_on(emulator_time(utime));
}

void ProtocolDrives::tick(int64_t utime)
{
  translation_.tick(emulator_time(utime));
  rotation_.tick(emulator_time(utime));
}

std::optional<DriveCommand> ProtocolDrives::command_at(int64_t /*utime*/)
{
  if (!powered_stage(translation_) || !powered_stage(rotation_)) return std::nullopt;
  return command_from_demands(translation_.demand_velocity(), rotation_.demand_velocity(), axes_);
}

void ProtocolDrives::report(const Simulator& sim)
{
  const EncoderReadings r = encoder_readings(sim, axes_);
  translation_.set_actual(r.translation.velocity, r.translation.position);
  rotation_.set_actual(r.rotation.velocity, r.rotation.position);
}

}  // namespace rgnav::sim
