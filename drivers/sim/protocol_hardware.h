// Protocol mode of rgnav_sim: the simulated B21r behind the real hardware protocols.
//   - an LMS 291 (drivers/sick Lms2xxEmulator) on a pseudo-terminal whose stable symlink is
//     laser_driver's port, serving the simulator's ray casts (SimScanSource);
//   - the translation and rotation CiA 402 drives (ProtocolDrives), each its own client of
//     the user-space virtual CAN bus at base_driver's socket ("drive-<node>", as the
//     drive_emulator process names them, so the bus's fault hooks address them alike); the
//     bus itself (VcanBroker) runs in this process unless an external vcan_broker serves it.
// advance() sub-steps the simulator by its physics step: frames waiting on the bus are
// handled and the drives ticked at the current simulated time, the physics step reads their
// demand velocities, and the resulting encoder state is reported back.
#pragma once

#include <chrono>
#include <memory>

#include "can/bus/can_interface.h"
#include "can/bus/vcan_broker.h"
#include "sick/lms2xx_emulator.h"
#include "sim/hardware_emulation.h"
#include "sim/protocol_drives.h"
#include "sim/protocol_laser.h"
#include "sim/protocol_options.h"

namespace rgnav::sim {

class ProtocolHardware final : public HardwareEmulation
{
 public:
  // Starts the bus (if internal), connects the drives and powers them on, opens the pty.
  // `sim` must outlive this object (the laser thread reads its scene) and is switched to
  // the drives as its command source. Throws can::CanError / std::runtime_error.
  ProtocolHardware(const ProtocolOptions& options, Simulator& sim);
  ~ProtocolHardware() override;
  ProtocolHardware(const ProtocolHardware&) = delete;
  ProtocolHardware& operator=(const ProtocolHardware&) = delete;

  StepOutput advance(std::chrono::microseconds dt) override;

  const ProtocolDrives& drives() const { return *drives_; }
  const SimScanSource& scans() const { return *scans_; }
  drivers::sick::Lms2xxEmulator::Stats laser_stats() const { return laser_->stats(); }
  std::string laser_port() const { return laser_->port_path(); }
  uint64_t can_send_failures() const { return send_failures_; }

 private:
  void pump(int64_t utime);

  const ProtocolOptions options_;
  Simulator& sim_;
  std::unique_ptr<can::VcanBroker> broker_;  // first in, last out: the clients need it
  std::unique_ptr<can::CanInterface> translation_bus_;
  std::unique_ptr<can::CanInterface> rotation_bus_;
  std::unique_ptr<ProtocolDrives> drives_;
  std::shared_ptr<SimScanSource> scans_;
  std::unique_ptr<drivers::sick::Lms2xxEmulator> laser_;
  uint64_t send_failures_ = 0;
};

}  // namespace rgnav::sim
