// The B21r synchro drive on a CANopen bus, as a single-threaded state machine with explicit
// time (BaseDriver runs it in a thread on a real CanInterface; tests run it on simulated time):
//  - a CanopenMaster with two CiA 402 drives: translation (wheel velocity) and rotation
//    (steering of all wheels = robot heading), both in profile velocity mode;
//  - velocity commands clamped and acceleration-limited, converted to counts/s;
//  - deadman: a command older than its deadline makes both drives do a controlled stop
//    (target 0, profile deceleration);
//  - faults (EMCY, drive fault, heartbeat loss, missing PDOs, bus-off) stop the robot: the
//    drives still reachable are held in quick stop until every drive is healthy again, then
//    the 402 state machine is re-run (recovery);
//  - safety stops asked for from outside (quick_stop(): a second source on BASE_CMD) hold both
//    drives in quick stop (0x6085 ramp) until released, then re-enable them like a recovery;
//  - odometry integrated exactly from both encoders once per SYNC cycle.
#pragma once

#include <linux/can.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "base_driver/base_driver_options.h"
#include "base_driver/synchro_odometry.h"
#include "master/canopen_master.h"

namespace rgnav::can::base {

enum class BaseStatus : uint8_t
{
  kOk,       // both drives enabled and following a fresh command
  kStopped,  // drives held at standstill: no or stale command, or still coming up
  kFault,    // a drive faulted, was lost, or the bus is off
};
const char* to_string(BaseStatus s);

struct VelocityCommand
{
  double v = 0.0;      // [m/s]
  double omega = 0.0;  // [rad/s]
};

struct BaseOdometry
{
  Pose2 pose;              // odom frame: where the driver started
  double v = 0.0;          // [m/s] measured (velocity actual of the translation drive)
  double omega = 0.0;      // [rad/s] measured (velocity actual of the rotation drive)
  double distance = 0.0;   // [m]
  uint64_t samples = 0;    // encoder sample pairs integrated
  BaseStatus status = BaseStatus::kStopped;
  std::string reason;      // why not OK ("" when OK)
  VelocityCommand commanded;  // what the drives are being asked for now (after limits)
};

class SynchroDriveController
{
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const can_frame&)>;

  SynchroDriveController(const BaseDriverOptions& options, Sink send);

  // A command received at `received`; void after `deadline` (never longer than the configured
  // command_deadline).
  void command(const VelocityCommand& cmd, Clock::time_point received, Clock::duration deadline);
  void handle(const can_frame& f, Clock::time_point now);
  void tick(Clock::time_point now);
  // Stop following commands for good (shutdown): targets 0 from now on.
  void release() { released_ = true; }
  // Holds both drives in quick stop while `hold` (a safety event: they ramp down at 0x6085, far
  // harder than the controlled stop's profile ramp); `why` is the odometry's reason meanwhile.
  // Released (once no drive is still ramping down), the drives are re-enabled (within
  // enable_timeout, else it is a fault) and follow fresh commands from standstill.
  void quick_stop(bool hold, const std::string& why = "");

  const BaseOdometry& odometry() const { return odom_; }
  bool at_standstill() const;
  const master::DriveMaster& translation() const { return *translation_; }
  const master::DriveMaster& rotation() const { return *rotation_; }
  const master::CanopenMaster& master() const { return master_; }

 private:
  void integrate_odometry();
  void release_quick_stop(Clock::time_point now);
  std::string fault_reason() const;

  BaseDriverOptions options_;
  master::CanopenMaster master_;
  master::DriveMaster* translation_;
  master::DriveMaster* rotation_;
  SynchroOdometry odometry_;
  BaseOdometry odom_;
  std::optional<VelocityCommand> command_;
  Clock::time_point command_expires_{};
  std::optional<Clock::time_point> last_tick_;
  VelocityCommand ramped_;  // acceleration-limited command
  bool ever_enabled_ = false;
  bool released_ = false;
  bool safety_stop_ = false;          // quick_stop(true) holds
  bool release_pending_ = false;      // quick_stop(false) asked while held
  std::string safety_stop_why_;
  std::optional<Clock::time_point> reenable_until_;  // after a safety stop: not enabled yet is no fault
  uint64_t used_samples_t_ = 0, used_samples_r_ = 0;
  uint32_t epoch_t_ = 0, epoch_r_ = 0;
};

}  // namespace rgnav::can::base
