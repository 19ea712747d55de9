// An emulated CiA 402 drive on CANopen (device side): NMT slave with boot-up message,
// heartbeat producer (0x1017), consumer of the master's heartbeat (0x1016; on loss: EMCY
// 0x8130 and the 0x6007 reaction, quick stop by default), expedited SDO server, RPDO/TPDO per
// the PDO configuration, SYNC, the 402 power state machine with quick stop, halt, fault
// reaction and fault reset, and the profile-velocity mode (0x6060 = 3): the demand velocity
// ramps to the target velocity 0x60FF with 0x6083 / 0x6084 (quick stop and fault reaction:
// 0x6085), and the encoder position integrates the actual velocity.
//
// The class is a pure state machine: frames in through handle(), time in through tick(now),
// frames out through the Sink; it never reads a clock or touches a socket, so tests, the
// `drive_emulator` process and the simulator can run it on real or simulated time.
//
// Physics hook (for drivers/sim): by default the motor follows the demand exactly (actual
// velocity = demand velocity, position integrated in tick()). A simulator calls
// attach_physics(true), reads demand_velocity() each step, runs its own model, and reports
// the result with set_actual(velocity, position); the drive then publishes those values in
// 0x606C / 0x6064 and checks the following error against them (fault 0x8611 if enabled).
#pragma once

#include <linux/can.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>

#include "canopen/cia402.h"
#include "canopen/protocol.h"
#include "emulator/device_pdos.h"
#include "emulator/drive_object_dictionary.h"
#include "emulator/object_dictionary.h"

namespace rgnav::can::emulator {

struct DriveEmulatorOptions
{
  uint8_t node_id = 2;
  DriveIdentity identity;
  DriveDefaults defaults;
  // Following error monitoring, only with physics attached: fault 0x8611 when
  // |actual - demand| > window [counts/s] for longer than `following_error_time`. 0 = off.
  uint32_t following_error_window = 0;
  std::chrono::milliseconds following_error_time{200};
};

class DriveEmulator
{
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const can_frame&)>;
  using PowerState = canopen::cia402::PowerState;

  DriveEmulator(DriveEmulatorOptions options, Sink send);

  // Boots the device: sends the boot-up message and enters pre-operational.
  void power_on(Clock::time_point now);
  // The device goes silent (no frames in or out) until power_on(); a dead node.
  void power_off();
  bool powered() const { return powered_; }

  void handle(const can_frame& f, Clock::time_point now);
  // Advances ramps, position, heartbeats, the heartbeat consumer and event-driven TPDOs.
  void tick(Clock::time_point now);

  // --- physics hook ---
  double demand_velocity() const { return velocity_demand_; }  // [counts/s]
  void attach_physics(bool attached) { physics_attached_ = attached; }
  void set_actual(double velocity_counts_per_s, double position_counts);

  // --- fault injection ---
  // A fault condition (e.g. emcy::kContinuousOverCurrent): EMCY, fault reaction, Fault. It
  // stays present, so fault resets fail, until clear_fault_condition().
  void inject_fault(uint16_t error_code);
  void clear_fault_condition() { fault_condition_.reset(); }

  // --- observation ---
  uint8_t node_id() const { return options_.node_id; }
  canopen::NmtState nmt_state() const { return nmt_; }
  PowerState power_state() const { return power_; }
  double actual_velocity() const { return velocity_actual_; }  // [counts/s]
  double actual_position() const { return position_; }         // [counts], not wrapped
  int32_t target_velocity() const { return od_.get_signed(canopen::cia402::kTargetVelocity); }
  bool master_heartbeat_lost() const { return consumer_lost_; }
  const ObjectDictionary& od() const { return od_; }

 private:
  void boot(Clock::time_point now, bool reset_application);
  void on_nmt(const can_frame& f, Clock::time_point now);
  void on_sdo(const can_frame& f);
  void on_heartbeat(const can_frame& f, Clock::time_point now);
  void on_write(uint16_t index, uint8_t sub);
  uint32_t check_write(uint16_t index, uint8_t sub, uint32_t value) const;
  void apply_controlword(uint16_t cw);
  void enter(PowerState s);
  void raise_fault(uint16_t error_code);
  void abort_connection();  // 0x6007 reaction to a communication loss
  void update_motion(double dt);
  void update_consumer(Clock::time_point now);
  void update_following_error(Clock::time_point now);
  void publish_state();
  void send(const can_frame& f);
  bool enabled() const;

  DriveEmulatorOptions options_;
  Sink send_;
  ObjectDictionary od_;
  DevicePdos pdos_;
  bool powered_ = false;
  bool physics_attached_ = false;
  canopen::NmtState nmt_ = canopen::NmtState::kPreOperational;
  PowerState power_ = PowerState::kNotReadyToSwitchOn;
  uint16_t previous_controlword_ = 0;
  double velocity_demand_ = 0.0;
  double velocity_actual_ = 0.0;
  double position_ = 0.0;
  bool limited_ = false;
  std::optional<uint16_t> fault_condition_;
  std::optional<Clock::time_point> last_tick_;
  Clock::time_point now_{};
  Clock::time_point next_heartbeat_{};
  // Heartbeat consumer: monitoring starts with the first heartbeat received (CiA 301 §7.2.8.3.2.2).
  bool consumer_armed_ = false;
  bool consumer_lost_ = false;
  Clock::time_point consumer_last_{};
  std::optional<Clock::time_point> following_error_since_;
};

}  // namespace rgnav::can::emulator
