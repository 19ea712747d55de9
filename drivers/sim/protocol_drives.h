// The B21r's two CiA 402 drives (translation and rotation) as the simulator sees them in
// protocol mode: DriveEmulators with the physics hook attached, run on the simulator's clock.
// They are the simulator's DriveCommandSource: every physics step reads their demand
// velocities (the profile-velocity ramp toward what base_driver set in 0x60FF) as the synchro
// drive's command; after the step report() hands back the actual velocities and encoder
// positions (protocol_conversions.h), which the drives publish in their TPDOs.
//
// No sockets here: frames in through handle_*(frame, utime), frames out through the sinks,
// so unit tests connect a master directly and the process connects VirtualCan clients.
#pragma once

#include <cstdint>
#include <optional>

#include "can/emulator/drive_emulator.h"
#include "sim/protocol_conversions.h"
#include "sim/simulator.h"

namespace rgnav::sim {

// Simulated time [us] as the emulator's clock: only differences matter to it.
inline can::emulator::DriveEmulator::Clock::time_point emulator_time(int64_t utime)
{
  return can::emulator::DriveEmulator::Clock::time_point(std::chrono::microseconds(utime));
}

class ProtocolDrives final : public DriveCommandSource
{
 public:
  using Sink = can::emulator::DriveEmulator::Sink;
  using DriveEmulator = can::emulator::DriveEmulator;

  // Node ids from the axes; the sinks put a drive's frames on the bus.
  ProtocolDrives(const DriveAxes& axes, Sink translation_out, Sink rotation_out);

  // Boot-up messages; the drives then wait in pre-operational for the master.
  void power_on(int64_t utime);
  bool ramped_by_drives() const override { return true; }
  void handle_translation(const can_frame& f, int64_t utime) { translation_.handle(f, emulator_time(utime)); }
  void handle_rotation(const can_frame& f, int64_t utime) { rotation_.handle(f, emulator_time(utime)); }
  // Ramps, heartbeats, heartbeat consumers, event TPDOs.
  void tick(int64_t utime);

  // The demand velocities in m/s and rad/s; nullopt (the drive decelerates to a stop within
  // its own limits) unless both power stages are on.
  std::optional<DriveCommand> command_at(int64_t utime) override;
  // Actual velocities and encoder positions of the simulated base after a physics step.
  void report(const Simulator& sim);

  const DriveEmulator& translation() const { return translation_; }
  const DriveEmulator& rotation() const { return rotation_; }
  DriveEmulator& translation() { return translation_; }
  DriveEmulator& rotation() { return rotation_; }
  const DriveAxes& axes() const { return axes_; }

 private:
  const DriveAxes axes_;
  DriveEmulator translation_;
  DriveEmulator rotation_;
};

}  // namespace rgnav::sim
