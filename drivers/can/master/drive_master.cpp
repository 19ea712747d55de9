#include "master/drive_master.h"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "bus/can_frames.h"
#include "canopen/sdo.h"

namespace rgnav::can::master {

namespace cia402 = canopen::cia402;
namespace emcy = canopen::emcy;
using canopen::NmtCommand;
using canopen::NmtState;
using PowerState = cia402::PowerState;

const char* to_string(DriveState s)
{
  switch (s) {
    case DriveState::kOffline: return "offline";
    case DriveState::kConfiguring: return "configuring";
    case DriveState::kEnabling: return "enabling";
    case DriveState::kEnabled: return "enabled";
    case DriveState::kFault: return "fault";
    case DriveState::kLost: return "lost";
  }
  return "?";
}

DriveMaster::DriveMaster(DriveMasterOptions options, SdoClient* sdo, Sink send)
    : options_(options), sdo_(sdo), send_(std::move(send))
{
}

std::vector<DriveMaster::Step> DriveMaster::configuration_steps() const
{
  const uint32_t n = options_.node_id;
  const auto hb = static_cast<uint32_t>(options_.heartbeat_period.count());
  const uint32_t consumer =
      (static_cast<uint32_t>(options_.master_node_id) << 16) | static_cast<uint32_t>(options_.master_heartbeat_timeout.count());
  std::vector<Step> s;
  auto up = [&s](uint16_t i, uint8_t sub, std::function<std::string(uint32_t)> check) {
    s.push_back({true, i, sub, 0, 0, std::move(check)});
  };
  auto down = [&s](uint16_t i, uint8_t sub, uint32_t v, uint8_t size) { s.push_back({false, i, sub, v, size, nullptr}); };
  up(0x1000, 0, [](uint32_t v) {
    return (v & 0xFFFF) == cia402::kDeviceProfile ? "" : "device type 0x" + std::to_string(v) + " is no CiA 402 drive";
  });
  up(cia402::kSupportedDriveModes, 0, [](uint32_t v) {
    return (v & cia402::kSupportsProfileVelocity) ? "" : "drive does not support profile velocity mode";
  });
  // A PDO with two mapped entries, by the CiA 301 procedure: invalidate, clear the mapping,
  // write the entries, set their count, set the transmission type, validate.
  auto map_pdo = [&down](uint16_t communication, uint16_t mapping, uint32_t cob_id, uint32_t first, uint32_t second,
                         uint32_t type) {
    down(communication, 1, canopen::kCobIdInvalid | cob_id, 4);
    down(mapping, 0, 0, 1);
    down(mapping, 1, first, 4);
    down(mapping, 2, second, 4);
    down(mapping, 0, 2, 1);
    down(communication, 2, type, 1);
    down(communication, 1, cob_id, 4);
  };
  down(0x1017, 0, hb, 2);
  down(0x1016, 1, consumer, 4);
  // RPDO1: controlword + target velocity, applied on reception (type 255).
  map_pdo(0x1400, 0x1600, canopen::kRpdo1 + n, 0x60400010, 0x60FF0020, 0xFF);
  // TPDO1: statusword + position actual, on every SYNC.
  map_pdo(0x1800, 0x1A00, canopen::kTpdo1 + n, 0x60410010, 0x60640020, 1);
  // TPDO2: velocity actual + modes of operation display, on every SYNC.
  map_pdo(0x1801, 0x1A01, canopen::kTpdo2 + n, 0x606C0020, 0x60610008, 1);
  // Profile velocity mode and its ramps.
  down(cia402::kProfileAcceleration, 0, options_.profile_acceleration, 4);
  down(cia402::kProfileDeceleration, 0, options_.profile_deceleration, 4);
  down(cia402::kQuickStopDeceleration, 0, options_.quick_stop_deceleration, 4);
  down(cia402::kMaxProfileVelocity, 0, options_.max_velocity, 4);
  down(cia402::kQuickStopOptionCode, 0, 2, 2);  // quick stop ramp, then switch on disabled
  down(cia402::kTargetVelocity, 0, 0, 4);
  down(cia402::kModesOfOperation, 0, static_cast<uint8_t>(cia402::kModeProfileVelocity), 1);
  return s;
}

void DriveMaster::begin_configuration(Clock::time_point now)
{
  ++generation_;
  if (may_have_rebooted_) ++epoch_;
  may_have_rebooted_ = false;
  retry_on_heartbeat_ = false;
  sdo_->cancel(options_.node_id);
  state_ = DriveState::kConfiguring;
  reason_ = "configuring";
  started_ = false;
  have_pdo_ = false;
  pdo_missing_ = false;
  configured_ok_ = false;
  controlword_ = 0;
  started_at_ = now;
  // Errors still present are reported again by the drive (statusword, EMCY) after the restart.
  emcy_.reset();
  // Configuration is done in pre-operational, where PDOs are off.
  send_(canopen::make_nmt(NmtCommand::kEnterPreOperational, options_.node_id));
  run_step(0, generation_);
}

void DriveMaster::run_step(size_t i, uint32_t generation)
{
  const auto steps = configuration_steps();
  if (i >= steps.size()) {
    configured_ok_ = true;
    return;
  }
  const Step st = steps[i];
  auto done = [this, i, generation, st](const SdoResult& r) {
    if (generation != generation_) return;  // a newer configuration run took over
    if (!r.ok) {
      configuration_failed(r.error);
      return;
    }
    if (st.check) {
      const std::string why = st.check(r.value);
      if (!why.empty()) {
        configuration_failed(why);
        return;
      }
    }
    run_step(i + 1, generation);
  };
  if (st.upload)
    sdo_->upload(options_.node_id, st.index, st.sub, done);
  else
    sdo_->download(options_.node_id, st.index, st.sub, st.value, st.size, done);
}

void DriveMaster::configuration_failed(const std::string& why)
{
  go_offline("configuration failed: " + why, now_ + options_.retry_interval);
}

void DriveMaster::go_offline(const std::string& why, Clock::time_point retry_at)
{
  if (reason_ != why) spdlog::warn("drive {}: {}", options_.node_id, why);
  ++generation_;
  sdo_->cancel(options_.node_id);
  state_ = DriveState::kOffline;
  reason_ = why;
  started_ = false;
  retry_at_ = retry_at;
}

void DriveMaster::on_heartbeat(NmtState nmt, Clock::time_point now)
{
  now_ = now;
  if (state_ == DriveState::kLost) {
    spdlog::info("drive {}: heartbeat back ({})", options_.node_id, canopen::to_string(nmt));
    if (nmt == NmtState::kBootUp) may_have_rebooted_ = true;
    go_offline("heartbeat back, reconfiguring", now);
    return;
  }
  if (nmt == NmtState::kBootUp) {
    // The node (re)booted: whatever was configured is gone.
    may_have_rebooted_ = true;
    if (state_ != DriveState::kOffline || now < retry_at_) go_offline("node rebooted", now);
    return;
  }
  const bool running = state_ == DriveState::kEnabling || state_ == DriveState::kEnabled || state_ == DriveState::kFault;
  // Heartbeats sent before our NMT start was processed may still report pre-operational.
  if (running && nmt != NmtState::kOperational && now - started_at_ > options_.heartbeat_timeout)
    go_offline(std::string("node left operational (") + canopen::to_string(nmt) + ")", now);
  // Back after a bus-off: configure now rather than at the next probe.
  if (state_ == DriveState::kOffline && retry_on_heartbeat_) {
    retry_on_heartbeat_ = false;
    retry_at_ = now;
  }
}

void DriveMaster::on_heartbeat_lost(Clock::time_point now)
{
  now_ = now;
  ++generation_;
  sdo_->cancel(options_.node_id);
  state_ = DriveState::kLost;
  started_ = false;
  reason_ = "heartbeat lost (no heartbeat for " + std::to_string(options_.heartbeat_timeout.count()) + " ms)";
  spdlog::error("drive {}: {}", options_.node_id, reason_);
}

void DriveMaster::on_bus_off(Clock::time_point now)
{
  now_ = now;
  go_offline("CAN bus-off", now + options_.retry_interval);
  retry_on_heartbeat_ = true;
}

void DriveMaster::on_emcy(const emcy::Emergency& e, Clock::time_point now)
{
  now_ = now;
  if (e.error_code == emcy::kNoError) {
    if (emcy_) spdlog::info("drive {}: error reset ({})", options_.node_id, emcy::describe(*emcy_));
    emcy_.reset();
  } else {
    spdlog::error("drive {}: {} (error register 0x{:02X})", options_.node_id, emcy::describe(e.error_code),
                  e.error_register);
    emcy_ = e.error_code;
  }
  update_state(now);
}

bool DriveMaster::on_pdo(const can_frame& f, Clock::time_point now)
{
  const canid_t id = f.can_id & CAN_SFF_MASK;
  if (id == canopen::kTpdo1 + options_.node_id && f.can_dlc >= 6) {
    now_ = now;
    statusword_ = static_cast<uint16_t>(canopen::get_le(f.data, 2));
    position_ = static_cast<int32_t>(canopen::get_le(f.data + 2, 4));
    power_ = cia402::decode_statusword(statusword_);
    ++position_samples_;
    last_pdo_ = now;
    have_pdo_ = true;
    pdo_missing_ = false;
    update_state(now);
    return true;
  }
  if (id == canopen::kTpdo2 + options_.node_id && f.can_dlc >= 5) {
    velocity_ = static_cast<int32_t>(canopen::get_le(f.data, 4));
    mode_display_ = static_cast<int8_t>(f.data[4]);
    return true;
  }
  return false;
}

void DriveMaster::update_state(Clock::time_point now)
{
  if (!started_) return;
  const bool drive_fault = power_ == PowerState::kFault || power_ == PowerState::kFaultReactionActive;
  if (drive_fault || emcy_ || pdo_missing_) {
    state_ = DriveState::kFault;
    if (pdo_missing_)
      reason_ = "no TPDO for " + std::to_string(options_.pdo_timeout.count()) + " ms";
    else if (emcy_)
      reason_ = emcy::describe(*emcy_);
    else
      reason_ = std::string("drive in ") + cia402::to_string(power_);
    return;
  }
  if (state_ == DriveState::kFault) {
    // Fault gone (reset succeeded / error reset received): walk the state machine again.
    state_ = DriveState::kEnabling;
    started_at_ = now;
    reason_ = "enabling after fault";
  }
  const bool enabled = have_pdo_ && power_ == PowerState::kOperationEnabled &&
                       mode_display_ == cia402::kModeProfileVelocity && !hold_quick_stop_;
  if (enabled) {
    if (state_ != DriveState::kEnabled) spdlog::info("drive {}: operation enabled", options_.node_id);
    state_ = DriveState::kEnabled;
    reason_.clear();
  } else if (hold_quick_stop_) {
    if (state_ == DriveState::kEnabled) state_ = DriveState::kEnabling;
    reason_ = "held in quick stop until every drive is healthy";
  } else if (state_ == DriveState::kEnabled) {
    state_ = DriveState::kEnabling;
    started_at_ = now;
    reason_ = std::string("drive left operation enabled (") + cia402::to_string(power_) + ")";
  }
}

void DriveMaster::tick(Clock::time_point now)
{
  now_ = now;
  switch (state_) {
    case DriveState::kOffline:
      if (now >= retry_at_) begin_configuration(now);
      break;
    case DriveState::kConfiguring:
      if (configured_ok_) {
        send_(canopen::make_nmt(NmtCommand::kStart, options_.node_id));
        started_ = true;
        state_ = DriveState::kEnabling;
        reason_ = "enabling";
        started_at_ = now;
        last_pdo_ = now;
        configured_ok_ = false;
      }
      break;
    case DriveState::kEnabling:
      if (hold_quick_stop_) started_at_ = now;  // held on purpose: not a timeout
      if (now - started_at_ > options_.enable_timeout)
        go_offline(std::string("no Operation enabled within ") + std::to_string(options_.enable_timeout.count()) +
                       " ms (drive in " + cia402::to_string(power_) + ")",
                   now);
      [[fallthrough]];
    case DriveState::kEnabled:
    case DriveState::kFault:
      if (started_ && now - last_pdo_ > options_.pdo_timeout && !pdo_missing_) {
        pdo_missing_ = true;
        spdlog::error("drive {}: no TPDO for {} ms", options_.node_id, options_.pdo_timeout.count());
      }
      update_state(now);
      break;
    case DriveState::kLost:
      break;
  }
}

std::optional<can_frame> DriveMaster::rpdo(Clock::time_point now)
{
  if (!started_) return std::nullopt;
  uint16_t cw;
  const bool fault_state = power_ == PowerState::kFault;
  if (fault_state) {
    // Rising edge of bit 7, at most every fault_reset_interval.
    if (!(controlword_ & cia402::cw::kFaultReset) && now - last_fault_reset_ >= options_.fault_reset_interval) {
      cw = cia402::cw::kCmdFaultReset;
      last_fault_reset_ = now;
    } else {
      cw = cia402::cw::kCmdDisableVoltage;
    }
  } else if (hold_quick_stop_ || emcy_ || pdo_missing_ || power_ == PowerState::kFaultReactionActive) {
    cw = cia402::cw::kCmdQuickStop;
  } else {
    cw = cia402::controlword_towards_enabled(power_, controlword_);
  }
  controlword_ = cw;
  const int32_t target = state_ == DriveState::kEnabled && !hold_quick_stop_ ? target_ : 0;
  uint8_t data[6];
  canopen::put_le(data, cw, 2);
  canopen::put_le(data + 2, static_cast<uint32_t>(target), 4);
  return make_frame(canopen::kRpdo1 + options_.node_id, data, sizeof data);
}

}  // namespace rgnav::can::master
