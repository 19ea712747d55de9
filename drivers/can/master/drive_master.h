// Master-side handling of one CiA 402 drive in profile-velocity mode:
//  1. configuration over SDO (device type and supported modes checked; heartbeat producer and
//     consumer of the master's heartbeat; RPDO1 = controlword 0x6040 + target velocity 0x60FF,
//     event-driven; TPDO1 = statusword 0x6041 + position actual 0x6064 and TPDO2 = velocity
//     actual 0x606C + mode display 0x6061, both synchronous; ramps 0x6083/0x6084/0x6085;
//     0x607F; mode 0x6060 = 3), then NMT start;
//  2. the 402 power state machine over RPDO1 to Operation enabled, fault reset included;
//  3. supervision: EMCY, heartbeat loss, node reboots or leaving operational, missing TPDOs.
// Any failure drops back to a state from which the sequence is re-run (recovery), so the
// drive comes back by itself once the cause is gone. Pure state machine: time comes in, frames
// go out through the Sink / SdoClient; no clock, no socket.
#pragma once

#include <linux/can.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "canopen/cia402.h"
#include "canopen/emcy.h"
#include "canopen/protocol.h"
#include "master/sdo_client.h"

namespace rgnav::can::master {

struct DriveMasterOptions
{
  uint8_t node_id = 2;
  uint8_t master_node_id = 1;
  std::chrono::milliseconds heartbeat_period{20};         // drive's producer time (0x1017)
  std::chrono::milliseconds heartbeat_timeout{80};        // master's consumer time for the drive
  std::chrono::milliseconds master_heartbeat_timeout{100};  // drive's consumer time for the master (0x1016)
  uint32_t profile_acceleration = 10000;     // 0x6083 [counts/s^2]
  uint32_t profile_deceleration = 10000;     // 0x6084 [counts/s^2]
  uint32_t quick_stop_deceleration = 50000;  // 0x6085 [counts/s^2]
  uint32_t max_velocity = 100000;            // 0x607F [counts/s]
  std::chrono::milliseconds pdo_timeout{100};           // TPDO1 expected every SYNC
  std::chrono::milliseconds fault_reset_interval{300};  // between fault-reset attempts
  std::chrono::milliseconds retry_interval{500};        // after a failed configuration
  std::chrono::milliseconds enable_timeout{1500};       // NMT start -> Operation enabled
};

enum class DriveState : uint8_t
{
  kOffline,      // not configured; (re)configuration is tried every retry_interval
  kConfiguring,  // SDO sequence running
  kEnabling,     // NMT operational, walking the 402 state machine
  kEnabled,      // Operation enabled in profile velocity: follows the target velocity
  kFault,        // EMCY / drive fault / missing TPDOs: held stopped, fault reset attempted
  kLost,         // heartbeat lost
};
const char* to_string(DriveState s);

class DriveMaster
{
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const can_frame&)>;
  using PowerState = canopen::cia402::PowerState;

  DriveMaster(DriveMasterOptions options, SdoClient* sdo, Sink send);

  // --- events routed by CanopenMaster ---
  void on_heartbeat(canopen::NmtState state, Clock::time_point now);
  void on_heartbeat_lost(Clock::time_point now);
  void on_emcy(const canopen::emcy::Emergency& e, Clock::time_point now);
  // True if `f` is one of this drive's TPDOs.
  bool on_pdo(const can_frame& f, Clock::time_point now);
  void on_bus_off(Clock::time_point now);
  void tick(Clock::time_point now);
  // This cycle's RPDO1 (controlword + target velocity), once NMT start was sent.
  std::optional<can_frame> rpdo(Clock::time_point now);

  // --- commands ---
  void set_target_velocity(int32_t counts_per_s) { target_ = counts_per_s; }
  // Hold the drive in quick stop (it ramps down with 0x6085, then stays disabled).
  void set_quick_stop(bool hold) { hold_quick_stop_ = hold; }

  // --- status ---
  uint8_t node_id() const { return options_.node_id; }
  DriveState state() const { return state_; }
  PowerState power_state() const { return power_; }
  bool enabled() const { return state_ == DriveState::kEnabled; }
  const std::string& reason() const { return reason_; }  // why not enabled ("" when enabled)
  uint16_t statusword() const { return statusword_; }
  int32_t position() const { return position_; }  // [counts] 0x6064, wraps modulo 2^32
  int32_t velocity() const { return velocity_; }  // [counts/s] 0x606C
  uint64_t position_samples() const { return position_samples_; }
  // Increments whenever the position may have jumped (the drive booted, or was configured for
  // the first time); odometry re-baselines on a change. A drive that is reconfigured after its
  // heartbeat came back in a running NMT state did not reboot: its counter went on, and the
  // motion during the outage is in the next reading.
  uint32_t position_epoch() const { return epoch_; }
  std::optional<uint16_t> active_emcy() const { return emcy_; }

 private:
  struct Step
  {
    bool upload;
    uint16_t index;
    uint8_t sub;
    uint32_t value;
    uint8_t size;
    std::function<std::string(uint32_t)> check;  // uploads: "" if the value is acceptable
  };
  std::vector<Step> configuration_steps() const;
  void begin_configuration(Clock::time_point now);
  void run_step(size_t i, uint32_t generation);
  void configuration_failed(const std::string& why);
  void go_offline(const std::string& why, Clock::time_point retry_at);
  void update_state(Clock::time_point now);

  DriveMasterOptions options_;
  SdoClient* sdo_;
  Sink send_;
  DriveState state_ = DriveState::kOffline;
  std::string reason_ = "not configured yet";
  uint32_t generation_ = 0;
  uint32_t epoch_ = 0;
  bool may_have_rebooted_ = true;  // until configured once, and after a boot-up
  Clock::time_point now_{};
  Clock::time_point retry_at_{};
  Clock::time_point started_at_{};
  Clock::time_point last_pdo_{};
  Clock::time_point last_fault_reset_{};
  bool have_pdo_ = false;
  bool started_ = false;  // NMT start sent: RPDOs flow
  bool configured_ok_ = false;  // set by the last configuration step's callback
  bool retry_on_heartbeat_ = false;  // offline after a bus-off: the next heartbeat triggers configuration
  PowerState power_ = PowerState::kNotReadyToSwitchOn;
  uint16_t statusword_ = 0;
  int8_t mode_display_ = 0;
  int32_t position_ = 0;
  int32_t velocity_ = 0;
  uint64_t position_samples_ = 0;
  uint16_t controlword_ = 0;
  int32_t target_ = 0;
  bool hold_quick_stop_ = false;
  bool pdo_missing_ = false;
  std::optional<uint16_t> emcy_;
};

}  // namespace rgnav::can::master
