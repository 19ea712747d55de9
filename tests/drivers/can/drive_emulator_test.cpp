// The CiA 402 drive emulator on its own: power state machine, profile-velocity ramps,
// position integration, quick stop, heartbeat consumer, fault injection and reset, PDOs,
// and the physics hook the simulator uses.
#include <gtest/gtest.h>

#include <cmath>

#include "bus/can_frames.h"
#include "canopen/cia402.h"
#include "canopen/emcy.h"
#include "canopen/protocol.h"
#include "canopen/sdo.h"
#include "emulator/drive_emulator.h"

namespace rgnav::can::emulator {
namespace {

using namespace std::chrono_literals;
using canopen::NmtState;
using PowerState = canopen::cia402::PowerState;
namespace sdo = canopen::sdo;
namespace emcy = canopen::emcy;
using Clock = std::chrono::steady_clock;

class EmulatorFixture : public ::testing::Test
{
 protected:
  EmulatorFixture() : drive(make_options(), [this](const can_frame& f) { sent.push_back(f); })
  {
    drive.power_on(now);
    sent.clear();
  }
  static DriveEmulatorOptions make_options()
  {
    DriveEmulatorOptions o;
    o.node_id = 5;
    o.defaults.profile_acceleration = 1000;
    o.defaults.profile_deceleration = 2000;
    o.defaults.quick_stop_deceleration = 10000;
    return o;
  }
  // SDO write; returns the abort code (0 = confirmed).
  uint32_t write(uint16_t index, uint8_t sub, uint32_t value, uint8_t size)
  {
    sent.clear();
    drive.handle(sdo::download_request(5, index, sub, value, size), now);
    // Exactly one SDO answer (other frames, e.g. an EMCY caused by the write, may come too).
    std::vector<can_frame> answers;
    for (const auto& f : sent)
      if (frame_id(f) == 0x585) answers.push_back(f);
    EXPECT_EQ(answers.size(), 1u);
    if (answers.empty()) return 0xFFFFFFFF;
    const auto m = sdo::parse(answers.back());
    return m.type == sdo::Message::Type::kAbort ? m.abort_code : 0;
  }
  void controlword(uint16_t cw) { ASSERT_EQ(write(0x6040, 0, cw, 2), 0u); }
  void run(std::chrono::milliseconds d, std::chrono::milliseconds step = 1ms)
  {
    for (auto t = 0ms; t < d; t += step) {
      now += step;
      drive.tick(now);
    }
  }
  void enable_profile_velocity()
  {
    ASSERT_EQ(write(0x6060, 0, 3, 1), 0u);
    controlword(0x06);
    controlword(0x07);
    controlword(0x0F);
    ASSERT_EQ(drive.power_state(), PowerState::kOperationEnabled);
  }
  // Whether an EMCY with this error code was sent.
  bool sent_emcy(uint16_t error_code) const
  {
    for (const auto& f : sent)
      if (auto m = emcy::parse(f); m && m->error_code == error_code) return true;
    return false;
  }
  std::vector<can_frame> frames_with_id(canid_t id) const
  {
    std::vector<can_frame> out;
    for (const auto& f : sent)
      if (frame_id(f) == id) out.push_back(f);
    return out;
  }

  Clock::time_point now = Clock::time_point(std::chrono::seconds(100));
  std::vector<can_frame> sent;
  DriveEmulator drive;
};

TEST_F(EmulatorFixture, PowerStateMachineToOperationEnabledAndBack)
{
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchOnDisabled);
  EXPECT_EQ(drive.od().get(0x6041) & 0x4F, 0x40u);
  controlword(0x0F);  // enable operation from switch on disabled: not a legal transition
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchOnDisabled);
  controlword(0x06);
  EXPECT_EQ(drive.power_state(), PowerState::kReadyToSwitchOn);
  controlword(0x07);
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchedOn);
  controlword(0x0F);
  EXPECT_EQ(drive.power_state(), PowerState::kOperationEnabled);
  const uint16_t s = static_cast<uint16_t>(drive.od().get(0x6041));
  EXPECT_EQ(s & 0x6F, 0x27);
  EXPECT_TRUE(s & canopen::cia402::sw::kVoltageEnabled);
  EXPECT_TRUE(s & canopen::cia402::sw::kRemote);
  controlword(0x07);  // disable operation (5)
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchedOn);
  controlword(0x06);  // shutdown (6)
  EXPECT_EQ(drive.power_state(), PowerState::kReadyToSwitchOn);
  controlword(0x00);  // disable voltage (7)
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchOnDisabled);
}

TEST_F(EmulatorFixture, ProfileVelocityRampAndEncoderIntegration)
{
  enable_profile_velocity();
  ASSERT_EQ(write(0x60FF, 0, 500, 4), 0u);
  run(250ms);
  EXPECT_NEAR(drive.actual_velocity(), 250.0, 1.0) << "1000 counts/s^2 for 0.25 s";
  EXPECT_FALSE(drive.od().get(0x6041) & canopen::cia402::sw::kTargetReached);
  run(750ms);
  EXPECT_DOUBLE_EQ(drive.actual_velocity(), 500.0);
  EXPECT_TRUE(drive.od().get(0x6041) & canopen::cia402::sw::kTargetReached);
  // Position: 0.5 * a * t^2 during the ramp (125 counts), then 500 counts/s for 0.5 s.
  EXPECT_NEAR(drive.actual_position(), 125.0 + 250.0, 0.5);
  EXPECT_EQ(drive.od().get_signed(0x6064), 375);
  EXPECT_EQ(drive.od().get_signed(0x606C), 500);
  // Deceleration uses 0x6084 (2000 counts/s^2): 500 -> 0 in 0.25 s.
  ASSERT_EQ(write(0x60FF, 0, 0, 4), 0u);
  run(200ms);
  EXPECT_NEAR(drive.actual_velocity(), 100.0, 1.0);
  run(100ms);
  EXPECT_EQ(drive.actual_velocity(), 0.0);
  // Reversing: the ramp goes through zero with decel then accel.
  ASSERT_EQ(write(0x60FF, 0, static_cast<uint32_t>(-300), 4), 0u);
  run(1000ms);
  EXPECT_DOUBLE_EQ(drive.actual_velocity(), -300.0);
  // Halt (bit 8) stops on the profile deceleration and stays enabled.
  controlword(0x010F);
  run(200ms);
  EXPECT_EQ(drive.actual_velocity(), 0.0);
  EXPECT_EQ(drive.power_state(), PowerState::kOperationEnabled);
}

TEST_F(EmulatorFixture, VelocityIsClampedToMaxProfileVelocity)
{
  enable_profile_velocity();
  ASSERT_EQ(write(0x607F, 0, 200, 4), 0u);
  ASSERT_EQ(write(0x60FF, 0, 5000, 4), 0u);
  run(1000ms);
  EXPECT_DOUBLE_EQ(drive.actual_velocity(), 200.0);
  EXPECT_TRUE(drive.od().get(0x6041) & canopen::cia402::sw::kInternalLimit);
}

TEST_F(EmulatorFixture, QuickStopRampsWithQuickStopDecelerationThenDisables)
{
  enable_profile_velocity();
  ASSERT_EQ(write(0x60FF, 0, 1000, 4), 0u);
  run(1500ms);
  ASSERT_DOUBLE_EQ(drive.actual_velocity(), 1000.0);
  controlword(0x02);
  EXPECT_EQ(drive.power_state(), PowerState::kQuickStopActive);
  EXPECT_EQ(drive.od().get(0x6041) & 0x6F, 0x07u);
  run(50ms);
  EXPECT_NEAR(drive.actual_velocity(), 500.0, 10.0) << "10000 counts/s^2";
  run(60ms);
  EXPECT_EQ(drive.actual_velocity(), 0.0);
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchOnDisabled) << "quick stop option code 2";
}

TEST_F(EmulatorFixture, MasterHeartbeatLossMakesAQuickStop)
{
  ASSERT_EQ(write(0x1016, 1, (1u << 16) | 100u, 4), 0u);  // watch node 1, 100 ms
  drive.handle(canopen::make_nmt(canopen::NmtCommand::kStart, 5), now);
  enable_profile_velocity();
  ASSERT_EQ(write(0x60FF, 0, 1000, 4), 0u);
  for (int i = 0; i < 100; ++i) {  // 2 s of master heartbeats every 20 ms
    run(20ms);
    drive.handle(canopen::make_heartbeat(1, NmtState::kOperational), now);
  }
  ASSERT_DOUBLE_EQ(drive.actual_velocity(), 1000.0);
  sent.clear();
  run(100ms);
  EXPECT_FALSE(drive.master_heartbeat_lost()) << "exactly the consumer time is not yet a loss";
  run(2ms);
  EXPECT_TRUE(drive.master_heartbeat_lost());
  auto e = frames_with_id(0x85);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(emcy::parse(e[0])->error_code, emcy::kHeartbeatError);
  EXPECT_EQ(drive.power_state(), PowerState::kQuickStopActive);
  EXPECT_EQ(drive.nmt_state(), NmtState::kPreOperational);
  run(150ms);
  EXPECT_EQ(drive.actual_velocity(), 0.0);
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchOnDisabled);
  // The master comes back: error reset EMCY.
  sent.clear();
  drive.handle(canopen::make_heartbeat(1, NmtState::kOperational), now);
  e = frames_with_id(0x85);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(emcy::parse(e[0])->error_code, emcy::kNoError);
}

TEST_F(EmulatorFixture, InjectedFaultSendsEmcyAndNeedsResetAfterItClears)
{
  enable_profile_velocity();
  ASSERT_EQ(write(0x60FF, 0, 1000, 4), 0u);
  run(1500ms);
  sent.clear();
  drive.inject_fault(emcy::kContinuousOverCurrent);
  auto e = frames_with_id(0x85);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(emcy::parse(e[0])->error_code, 0x2310);
  EXPECT_EQ(emcy::parse(e[0])->error_register, emcy::kRegGeneric | emcy::kRegCurrent);
  EXPECT_EQ(drive.power_state(), PowerState::kFaultReactionActive);
  run(200ms);
  EXPECT_EQ(drive.actual_velocity(), 0.0);
  EXPECT_EQ(drive.power_state(), PowerState::kFault);
  // Reset while the condition persists: stays in fault.
  controlword(0x00);
  controlword(0x80);
  EXPECT_EQ(drive.power_state(), PowerState::kFault);
  drive.clear_fault_condition();
  controlword(0x80);  // no edge: nothing
  EXPECT_EQ(drive.power_state(), PowerState::kFault);
  controlword(0x00);
  sent.clear();
  controlword(0x80);
  EXPECT_EQ(drive.power_state(), PowerState::kSwitchOnDisabled);
  EXPECT_EQ(drive.od().get(0x1001), 0u);
  EXPECT_TRUE(sent_emcy(emcy::kNoError));
}

TEST_F(EmulatorFixture, PdosAfterConfigurationAndNmtStart)
{
  // TPDO1 default: statusword only, synchronous. Remap to statusword + position.
  ASSERT_EQ(write(0x1800, 1, 0x80000185, 4), 0u);
  ASSERT_EQ(write(0x1A00, 0, 0, 1), 0u);
  ASSERT_EQ(write(0x1A00, 2, 0x60640020, 4), 0u);
  ASSERT_EQ(write(0x1A00, 0, 2, 1), 0u);
  ASSERT_EQ(write(0x1800, 1, 0x185, 4), 0u);
  // RPDO1: controlword + target velocity.
  ASSERT_EQ(write(0x1400, 1, 0x80000205, 4), 0u);
  ASSERT_EQ(write(0x1600, 0, 0, 1), 0u);
  ASSERT_EQ(write(0x1600, 2, 0x60FF0020, 4), 0u);
  ASSERT_EQ(write(0x1600, 0, 2, 1), 0u);
  ASSERT_EQ(write(0x1400, 1, 0x205, 4), 0u);
  ASSERT_EQ(write(0x6060, 0, 3, 1), 0u);
  sent.clear();
  drive.handle(canopen::make_sync(), now);
  EXPECT_TRUE(frames_with_id(0x185).empty()) << "no PDOs in pre-operational";
  drive.handle(canopen::make_nmt(canopen::NmtCommand::kStart, 5), now);
  for (uint16_t cw : {0x06, 0x07, 0x0F}) {
    uint8_t d[6];
    canopen::put_le(d, cw, 2);
    canopen::put_le(d + 2, 400, 4);
    drive.handle(make_frame(0x205, d, 6), now);
  }
  EXPECT_EQ(drive.power_state(), PowerState::kOperationEnabled);
  EXPECT_EQ(drive.target_velocity(), 400);
  run(1000ms);
  sent.clear();
  drive.handle(canopen::make_sync(), now);
  auto t = frames_with_id(0x185);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].can_dlc, 6);
  EXPECT_EQ(canopen::get_le(t[0].data, 2) & 0x6F, 0x27u);
  EXPECT_EQ(static_cast<int32_t>(canopen::get_le(t[0].data + 2, 4)), drive.od().get_signed(0x6064));
  EXPECT_GT(drive.od().get_signed(0x6064), 0);
}

TEST_F(EmulatorFixture, PhysicsHookAndFollowingError)
{
  DriveEmulatorOptions o = make_options();
  o.following_error_window = 100;
  o.following_error_time = 50ms;
  sent.clear();
  DriveEmulator d(o, [this](const can_frame& f) { sent.push_back(f); });
  d.attach_physics(true);
  d.power_on(now);
  auto w = [&](uint16_t i, uint32_t v, uint8_t s) { d.handle(sdo::download_request(5, i, 0, v, s), now); };
  w(0x6060, 3, 1);
  for (uint16_t cw : {0x06, 0x07, 0x0F}) w(0x6040, cw, 2);
  w(0x60FF, 1000, 4);
  // The "simulator" follows the demand, with its own position.
  double pos = 0.0;
  for (int i = 0; i < 500; ++i) {
    now += 1ms;
    d.tick(now);
    pos += d.demand_velocity() * 0.001;
    d.set_actual(d.demand_velocity(), pos);
  }
  EXPECT_NEAR(d.demand_velocity(), 500.0, 1.0);
  EXPECT_EQ(d.od().get_signed(0x606C), std::lround(d.demand_velocity()));
  EXPECT_EQ(d.od().get_signed(0x6064), std::lround(pos));
  // The robot hits a wall: actual stays 0 while the demand rises -> following error.
  sent.clear();
  for (int i = 0; i < 200 && d.power_state() == PowerState::kOperationEnabled; ++i) {
    now += 1ms;
    d.tick(now);
    d.set_actual(0.0, pos);
  }
  EXPECT_NE(d.power_state(), PowerState::kOperationEnabled);
  EXPECT_TRUE(sent_emcy(emcy::kFollowingError));
}

TEST_F(EmulatorFixture, PowerOffIsSilence)
{
  ASSERT_EQ(write(0x1017, 0, 10, 2), 0u);
  drive.power_off();
  sent.clear();
  run(100ms);
  drive.handle(sdo::upload_request(5, 0x1000, 0), now);
  EXPECT_TRUE(sent.empty());
  drive.power_on(now);
  ASSERT_FALSE(sent.empty());
  EXPECT_EQ(to_string(sent.front()), "705#00");
}

}  // namespace
}  // namespace rgnav::can::emulator
