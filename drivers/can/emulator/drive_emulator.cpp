#include "emulator/drive_emulator.h"

#include <algorithm>
#include <cmath>

#include "bus/can_frames.h"
#include "canopen/emcy.h"
#include "canopen/sdo.h"

namespace rgnav::can::emulator {

namespace cia402 = canopen::cia402;
namespace emcy = canopen::emcy;
namespace sdo = canopen::sdo;
using canopen::NmtCommand;
using canopen::NmtState;
using PowerState = cia402::PowerState;

namespace {

int32_t wrap_counts(double counts)
{
  // Encoders count modulo 2^32; the master differences consecutive readings.
  const auto wide = static_cast<int64_t>(std::llround(std::fmod(counts, 4294967296.0)));
  return static_cast<int32_t>(static_cast<uint32_t>(wide));
}

}  // namespace

DriveEmulator::DriveEmulator(DriveEmulatorOptions options, Sink send)
    : options_(std::move(options)),
      send_(std::move(send)),
      od_(make_drive_object_dictionary(options_.node_id, options_.identity, options_.defaults)),
      pdos_(&od_)
{
  od_.set_write_check([this](uint16_t i, uint8_t s, uint32_t v) { return check_write(i, s, v); });
  od_.set_write_hook([this](uint16_t i, uint8_t s) { on_write(i, s); });
}

void DriveEmulator::send(const can_frame& f)
{
  if (powered_ && send_) send_(f);
}

bool DriveEmulator::enabled() const
{
  return power_ == PowerState::kOperationEnabled || power_ == PowerState::kQuickStopActive ||
         power_ == PowerState::kFaultReactionActive;
}

void DriveEmulator::power_on(Clock::time_point now)
{
  powered_ = true;
  velocity_demand_ = 0.0;
  if (!physics_attached_) velocity_actual_ = 0.0;
  boot(now, true);
}

void DriveEmulator::power_off()
{
  powered_ = false;
  power_ = PowerState::kNotReadyToSwitchOn;
  velocity_demand_ = 0.0;
  if (!physics_attached_) velocity_actual_ = 0.0;
  last_tick_.reset();
}

void DriveEmulator::boot(Clock::time_point now, bool reset_application)
{
  now_ = now;
  if (reset_application) {
    od_.reset(0x0000, 0xFFFF);
    previous_controlword_ = 0;
    // Transition 1: initialisation done, the drive waits in switch on disabled.
    power_ = PowerState::kSwitchOnDisabled;
  } else {
    od_.reset(0x1000, 0x1FFF);
  }
  pdos_.reset();
  consumer_armed_ = false;
  consumer_lost_ = false;
  following_error_since_.reset();
  nmt_ = NmtState::kPreOperational;
  send(canopen::make_heartbeat(options_.node_id, NmtState::kBootUp));
  next_heartbeat_ = now;  // first heartbeat as soon as a producer time is configured
  if (fault_condition_ && reset_application) raise_fault(*fault_condition_);
  publish_state();
}

void DriveEmulator::handle(const can_frame& f, Clock::time_point now)
{
  if (!powered_ || is_error_frame(f) || is_extended(f)) return;
  now_ = now;
  const canid_t id = f.can_id & CAN_SFF_MASK;
  if (id == canopen::kNmt) {
    on_nmt(f, now);
  } else if (id == canopen::kSdoRx + options_.node_id) {
    if (nmt_ != NmtState::kStopped) on_sdo(f);
  } else if (id >= canopen::kHeartbeat && id <= canopen::kHeartbeat + 127) {
    on_heartbeat(f, now);
  } else if (id == (od_.get(0x1005) & CAN_SFF_MASK) && f.can_dlc <= 1) {
    if (nmt_ == NmtState::kOperational) pdos_.on_sync([this](const can_frame& out) { send(out); });
  } else if (nmt_ == NmtState::kOperational) {
    pdos_.on_rpdo(f);
  }
}

void DriveEmulator::on_nmt(const can_frame& f, Clock::time_point now)
{
  if (f.can_dlc != 2) return;
  if (f.data[1] != 0 && f.data[1] != options_.node_id) return;
  const NmtState before = nmt_;
  switch (static_cast<NmtCommand>(f.data[0])) {
    case NmtCommand::kStart: nmt_ = NmtState::kOperational; break;
    case NmtCommand::kStop: nmt_ = NmtState::kStopped; break;
    case NmtCommand::kEnterPreOperational: nmt_ = NmtState::kPreOperational; break;
    case NmtCommand::kResetNode: boot(now, true); return;
    case NmtCommand::kResetCommunication: boot(now, false); return;
    default: return;
  }
  // Losing the PDO channel while the motor is powered: react as to a connection loss.
  if (before == NmtState::kOperational && nmt_ != NmtState::kOperational) abort_connection();
  if (nmt_ != before) pdos_.reset();
}

void DriveEmulator::on_sdo(const can_frame& f)
{
  const sdo::Message m = sdo::parse(f);
  const canid_t reply = canopen::kSdoTx + options_.node_id;
  switch (m.type) {
    case sdo::Message::Type::kDownloadRequest: {
      const uint32_t abort = od_.sdo_write(m.index, m.subindex, m.value, m.size);
      send(abort ? sdo::abort(reply, m.index, m.subindex, abort)
                 : sdo::download_response(options_.node_id, m.index, m.subindex));
      break;
    }
    case sdo::Message::Type::kUploadRequest: {
      uint32_t value = 0;
      uint8_t size = 0;
      const uint32_t abort = od_.sdo_read(m.index, m.subindex, &value, &size);
      send(abort ? sdo::abort(reply, m.index, m.subindex, abort)
                 : sdo::upload_response(options_.node_id, m.index, m.subindex, value, size));
      break;
    }
    case sdo::Message::Type::kAbort:
      break;  // the client gave up; nothing in progress on this side
    default:
      send(sdo::abort(reply, m.index, m.subindex, sdo::kBadCommand));
  }
}

void DriveEmulator::on_heartbeat(const can_frame& f, Clock::time_point now)
{
  const uint32_t cfg = od_.get(0x1016, 1);
  const uint32_t node = (cfg >> 16) & 0x7F;
  if (node == 0 || (cfg & 0xFFFF) == 0) return;
  if ((f.can_id & CAN_SFF_MASK) != canopen::kHeartbeat + node || f.can_dlc < 1) return;
  consumer_last_ = now;
  consumer_armed_ = true;
  if (consumer_lost_) {
    consumer_lost_ = false;
    od_.set(0x1001, od_.get(0x1001) & ~emcy::kRegCommunication);
    send(emcy::make(options_.node_id, emcy::kNoError, static_cast<uint8_t>(od_.get(0x1001))));
  }
}

uint32_t DriveEmulator::check_write(uint16_t index, uint8_t sub, uint32_t value) const
{
  if (const uint32_t abort = pdos_.check_write(index, sub, value); abort) return abort;
  switch (index) {
    case cia402::kModesOfOperation: {
      const auto mode = static_cast<int8_t>(value);
      const bool supported = mode == 0 || (mode > 0 && mode <= 10 &&
                                           (od_.get(cia402::kSupportedDriveModes) & (1u << (mode - 1))));
      return supported ? 0 : sdo::kInvalidValue;
    }
    case cia402::kQuickStopOptionCode: {
      const auto code = static_cast<int16_t>(value);
      return (code == 1 || code == 2 || code == 5 || code == 6) ? 0 : sdo::kInvalidValue;
    }
    case 0x6007: return static_cast<int16_t>(value) >= 0 && static_cast<int16_t>(value) <= 3 ? 0 : sdo::kInvalidValue;
    case 0x1016: return sub == 1 && ((value >> 16) & 0xFF) > 127 ? sdo::kInvalidValue : 0;
    case 0x1005: return (value & 0x7FF) == 0 ? sdo::kInvalidValue : 0;
    default: return 0;
  }
}

void DriveEmulator::on_write(uint16_t index, uint8_t sub)
{
  if (index == cia402::kControlword) {
    apply_controlword(static_cast<uint16_t>(od_.get(index)));
  } else if (index == cia402::kModesOfOperation) {
    od_.set(cia402::kModesOfOperationDisplay, od_.get(index));
  } else if (index == 0x1017) {
    next_heartbeat_ = now_;
  } else if (index == 0x1016) {
    consumer_armed_ = false;  // monitoring restarts with the next heartbeat of the new producer
    consumer_lost_ = false;
  }
  publish_state();
}

void DriveEmulator::enter(PowerState s)
{
  power_ = s;
  publish_state();
}

void DriveEmulator::apply_controlword(uint16_t cw)
{
  using cia402::Command;
  const Command cmd = cia402::decode_controlword(cw, previous_controlword_);
  previous_controlword_ = cw;
  const int16_t qs_option = static_cast<int16_t>(od_.get(cia402::kQuickStopOptionCode));
  switch (power_) {
    case PowerState::kSwitchOnDisabled:
      if (cmd == Command::kShutdown) enter(PowerState::kReadyToSwitchOn);  // 2
      break;
    case PowerState::kReadyToSwitchOn:
      if (cmd == Command::kSwitchOn) enter(PowerState::kSwitchedOn);  // 3
      if (cmd == Command::kEnableOperation) enter(PowerState::kOperationEnabled);  // 3 + 4
      if (cmd == Command::kDisableVoltage || cmd == Command::kQuickStop) enter(PowerState::kSwitchOnDisabled);  // 7
      break;
    case PowerState::kSwitchedOn:
      if (cmd == Command::kEnableOperation) enter(PowerState::kOperationEnabled);  // 4
      if (cmd == Command::kShutdown) enter(PowerState::kReadyToSwitchOn);          // 6
      if (cmd == Command::kDisableVoltage || cmd == Command::kQuickStop) enter(PowerState::kSwitchOnDisabled);  // 10
      break;
    case PowerState::kOperationEnabled:
      if (cmd == Command::kSwitchOn) enter(PowerState::kSwitchedOn);               // 5
      if (cmd == Command::kShutdown) enter(PowerState::kReadyToSwitchOn);          // 8
      if (cmd == Command::kDisableVoltage) enter(PowerState::kSwitchOnDisabled);   // 9
      if (cmd == Command::kQuickStop) enter(PowerState::kQuickStopActive);         // 11
      break;
    case PowerState::kQuickStopActive:
      if (cmd == Command::kDisableVoltage) enter(PowerState::kSwitchOnDisabled);   // 12
      if (cmd == Command::kEnableOperation && qs_option >= 5) enter(PowerState::kOperationEnabled);  // 16
      break;
    case PowerState::kFault:
      if (cmd == Command::kFaultReset && !fault_condition_) {  // 15
        od_.set(0x1001, 0);
        send(emcy::make(options_.node_id, emcy::kNoError, 0));
        enter(PowerState::kSwitchOnDisabled);
      }
      break;
    case PowerState::kNotReadyToSwitchOn:
    case PowerState::kFaultReactionActive:
      break;
  }
  // Power stage off: an attached physics model gets no demand at all (the motor is free);
  // without physics the demand ramps down in update_motion() (a holding-brake model).
  if (!enabled() && physics_attached_) velocity_demand_ = 0.0;
}

void DriveEmulator::inject_fault(uint16_t error_code)
{
  fault_condition_ = error_code;
  raise_fault(error_code);
}

void DriveEmulator::raise_fault(uint16_t error_code)
{
  if (power_ == PowerState::kFault || power_ == PowerState::kFaultReactionActive) return;
  const uint8_t reg = static_cast<uint8_t>(od_.get(0x1001) | emcy::register_for(error_code));
  od_.set(0x1001, reg);
  if (nmt_ != NmtState::kStopped) send(emcy::make(options_.node_id, error_code, reg));
  // Transition 13; with the power stage off there is nothing to ramp down (14 at once).
  enter(enabled() ? PowerState::kFaultReactionActive : PowerState::kFault);
}

void DriveEmulator::abort_connection()
{
  switch (static_cast<int16_t>(od_.get(0x6007))) {
    case 1: raise_fault(emcy::kHeartbeatError); break;
    case 2: if (enabled()) enter(PowerState::kSwitchOnDisabled); break;
    case 3: if (power_ == PowerState::kOperationEnabled) enter(PowerState::kQuickStopActive); break;
    default: break;
  }
}

void DriveEmulator::update_consumer(Clock::time_point now)
{
  const uint32_t cfg = od_.get(0x1016, 1);
  const auto timeout = std::chrono::milliseconds(cfg & 0xFFFF);
  if (!consumer_armed_ || consumer_lost_ || timeout.count() == 0 || ((cfg >> 16) & 0x7F) == 0) return;
  if (now - consumer_last_ <= timeout) return;
  // Heartbeat event: report, stop the motor, and fall back to pre-operational (0x1029:1 = 0).
  consumer_lost_ = true;
  const uint8_t reg = static_cast<uint8_t>(od_.get(0x1001) | emcy::kRegCommunication);
  od_.set(0x1001, reg);
  send(emcy::make(options_.node_id, emcy::kHeartbeatError, reg));
  abort_connection();
  if (od_.get(0x1029, 1) == 0 && nmt_ == NmtState::kOperational) {
    nmt_ = NmtState::kPreOperational;
    pdos_.reset();
  }
}

void DriveEmulator::update_motion(double dt)
{
  const int32_t max_v = static_cast<int32_t>(std::min<uint32_t>(od_.get(cia402::kMaxProfileVelocity), INT32_MAX));
  const bool halted = (od_.get(cia402::kControlword) & cia402::cw::kHalt) != 0;
  const bool pv_mode = static_cast<int8_t>(od_.get(cia402::kModesOfOperationDisplay)) == cia402::kModeProfileVelocity;
  double target = 0.0;
  limited_ = false;
  if (power_ == PowerState::kOperationEnabled && pv_mode && !halted) {
    const int32_t t = od_.get_signed(cia402::kTargetVelocity);
    target = std::clamp<double>(t, -max_v, max_v);
    limited_ = target != t;
  }
  double rate;
  const int16_t qs_option = static_cast<int16_t>(od_.get(cia402::kQuickStopOptionCode));
  if (power_ == PowerState::kQuickStopActive && (qs_option == 1 || qs_option == 5)) {
    rate = od_.get(cia402::kProfileDeceleration);
  } else if (power_ != PowerState::kOperationEnabled) {
    rate = od_.get(cia402::kQuickStopDeceleration);  // quick stop, fault reaction, brake
  } else {
    const bool speeding_up = std::fabs(target) > std::fabs(velocity_demand_) && target * velocity_demand_ >= 0.0;
    rate = speeding_up ? od_.get(cia402::kProfileAcceleration) : od_.get(cia402::kProfileDeceleration);
  }
  const double step = rate * dt;
  const double err = target - velocity_demand_;
  velocity_demand_ = std::fabs(err) <= step ? target : velocity_demand_ + std::copysign(step, err);
  if (!physics_attached_) {
    // Trapezoidal integration of the ramp keeps the position exact for piecewise-linear velocity.
    position_ += 0.5 * (velocity_actual_ + velocity_demand_) * dt;
    velocity_actual_ = velocity_demand_;
  }
  const bool standstill = velocity_demand_ == 0.0 && (physics_attached_ ? std::fabs(velocity_actual_) < 1.0 : true);
  if (power_ == PowerState::kQuickStopActive && standstill && qs_option <= 4) enter(PowerState::kSwitchOnDisabled);
  if (power_ == PowerState::kFaultReactionActive && standstill) enter(PowerState::kFault);
}

void DriveEmulator::update_following_error(Clock::time_point now)
{
  const uint32_t window = options_.following_error_window;
  if (!physics_attached_ || window == 0 || power_ != PowerState::kOperationEnabled) {
    following_error_since_.reset();
    return;
  }
  if (std::fabs(velocity_actual_ - velocity_demand_) <= window) {
    following_error_since_.reset();
    return;
  }
  if (!following_error_since_) following_error_since_ = now;
  if (now - *following_error_since_ > options_.following_error_time) {
    following_error_since_.reset();
    raise_fault(emcy::kFollowingError);
  }
}

void DriveEmulator::set_actual(double velocity_counts_per_s, double position_counts)
{
  velocity_actual_ = velocity_counts_per_s;
  position_ = position_counts;
  publish_state();
}

void DriveEmulator::tick(Clock::time_point now)
{
  if (!powered_) return;
  now_ = now;
  const double dt = last_tick_ ? std::clamp(std::chrono::duration<double>(now - *last_tick_).count(), 0.0, 1.0) : 0.0;
  last_tick_ = now;
  update_motion(dt);
  update_following_error(now);
  update_consumer(now);
  publish_state();
  const auto period = std::chrono::milliseconds(od_.get(0x1017));
  if (period.count() > 0 && now >= next_heartbeat_) {
    send(canopen::make_heartbeat(options_.node_id, nmt_));
    next_heartbeat_ += period;
    if (next_heartbeat_ <= now) next_heartbeat_ = now + period;  // fell behind: no burst
  }
  if (nmt_ == NmtState::kOperational) pdos_.on_tick(now, [this](const can_frame& f) { send(f); });
}

void DriveEmulator::publish_state()
{
  namespace sw = cia402::sw;
  uint16_t s = cia402::statusword_bits(power_) | sw::kRemote;
  if (power_ != PowerState::kSwitchOnDisabled && power_ != PowerState::kNotReadyToSwitchOn && power_ != PowerState::kFault)
    s |= sw::kVoltageEnabled;
  const double target = power_ == PowerState::kOperationEnabled ? od_.get_signed(cia402::kTargetVelocity) : 0.0;
  if (std::fabs(velocity_demand_ - target) < 1.0) s |= sw::kTargetReached;
  if (limited_) s |= sw::kInternalLimit;
  if (consumer_lost_) s |= sw::kWarning;
  od_.set(cia402::kStatusword, s);
  od_.set(cia402::kVelocityDemand, static_cast<uint32_t>(static_cast<int32_t>(std::lround(velocity_demand_))));
  od_.set(cia402::kVelocityActual, static_cast<uint32_t>(static_cast<int32_t>(std::lround(velocity_actual_))));
  const auto pos = static_cast<uint32_t>(wrap_counts(position_));
  od_.set(cia402::kPositionActual, pos);
  od_.set(0x6063, pos);
  od_.set(0x6062, pos);
}

}  // namespace rgnav::can::emulator
