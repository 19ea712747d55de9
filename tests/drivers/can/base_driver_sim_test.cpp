// SynchroDriveController with two emulated drives on a simulated CAN bus (simulated time, so
// timing results are exact and never flaky): bring-up, commands, limits, odometry against an
// analytic arc, deadman, node loss, EMCY, bus-off, reboots, PDO loss — with recovery.
// The options are the shipped config/base_driver.yaml.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "base_driver/synchro_drive_controller.h"
#include "bus/can_frames.h"
#include "canopen/emcy.h"
#include "emulator/drive_emulator.h"
#include "sim_can_bus.h"

namespace rgnav::can::base {
namespace {

using namespace std::chrono_literals;
using emulator::DriveEmulator;
using PowerState = canopen::cia402::PowerState;
using Clock = std::chrono::steady_clock;

BaseDriverOptions shipped_options()
{
  const auto cfg = config::Config::load(std::string(RGNAV_SOURCE_DIR) + "/config/base_driver.yaml");
  return load_base_driver_options(cfg);
}

emulator::DriveEmulatorOptions drive_options(uint8_t node)
{
  emulator::DriveEmulatorOptions o;
  o.node_id = node;
  return o;
}

class BaseSim : public ::testing::Test
{
 protected:
  void SetUp() override { build(shipped_options()); }

  void build(const BaseDriverOptions& o)
  {
    options = o;
    bus = std::make_unique<testing::SimCanBus>();
    ctl_id = bus->add([this](const can_frame& f, Clock::time_point now) { ctl->handle(f, now); });
    t_id = bus->add([this](const can_frame& f, Clock::time_point now) { trans->handle(f, now); });
    r_id = bus->add([this](const can_frame& f, Clock::time_point now) { rot->handle(f, now); });
    ctl = std::make_unique<SynchroDriveController>(options, bus->sink(ctl_id));
    trans = std::make_unique<DriveEmulator>(drive_options(options.translation.node_id), bus->sink(t_id));
    rot = std::make_unique<DriveEmulator>(drive_options(options.rotation.node_id), bus->sink(r_id));
    trans->power_on(bus->now());
    rot->power_on(bus->now());
  }
  void step()
  {
    bus->advance(1ms);
    const auto now = bus->now();
    if (refresh_command && now >= next_command) {
      ctl->command(cmd, now, 500ms);
      next_command = now + 50ms;
    }
    ctl->tick(now);
    bus->deliver();
    trans->tick(now);
    rot->tick(now);
    bus->deliver();
  }
  void run(std::chrono::milliseconds d)
  {
    for (auto t = 0ms; t < d; t += 1ms) step();
  }
  // Runs until pred() holds; returns the simulated time it took, or nullopt after `limit`.
  std::optional<std::chrono::milliseconds> run_until(const std::function<bool()>& pred,
                                                     std::chrono::milliseconds limit)
  {
    for (auto t = 0ms; t <= limit; t += 1ms) {
      if (pred()) return t;
      step();
    }
    return std::nullopt;
  }
  bool both_enabled() const { return ctl->translation().enabled() && ctl->rotation().enabled(); }
  void bring_up()
  {
    auto t = run_until([this] { return both_enabled(); }, 3000ms);
    ASSERT_TRUE(t) << "drives not enabled: " << ctl->odometry().reason;
  }
  void drive(double v, double omega)
  {
    cmd = {v, omega};
    refresh_command = true;
  }
  double trans_velocity() const { return trans->actual_velocity() / options.translation.counts_per_unit; }
  double rot_velocity() const { return rot->actual_velocity() / options.rotation.counts_per_unit; }
  // A quick stop of the translation drive from v [m/s] (0x6085 ramp), rounded up to the ms.
  std::chrono::milliseconds quick_stop_ramp(double v) const
  {
    return std::chrono::milliseconds(static_cast<int64_t>(std::ceil(1000.0 * v / options.translation.quick_stop_deceleration)));
  }

  BaseDriverOptions options;
  std::unique_ptr<testing::SimCanBus> bus;
  int ctl_id = 0, t_id = 0, r_id = 0;
  std::unique_ptr<SynchroDriveController> ctl;
  std::unique_ptr<DriveEmulator> trans, rot;
  VelocityCommand cmd;
  bool refresh_command = false;
  Clock::time_point next_command{};
};

TEST_F(BaseSim, BringsBothDrivesToOperationEnabledInProfileVelocity)
{
  auto t = run_until([this] { return both_enabled(); }, 3000ms);
  ASSERT_TRUE(t);
  std::printf("[ figures  ] bring-up (boot-up -> both drives operation enabled): %lld ms simulated\n",
              static_cast<long long>(t->count()));
  for (auto* d : {trans.get(), rot.get()}) {
    EXPECT_EQ(d->nmt_state(), canopen::NmtState::kOperational);
    EXPECT_EQ(d->power_state(), PowerState::kOperationEnabled);
    EXPECT_EQ(d->od().get_signed(0x6061), 3) << "profile velocity mode";
    EXPECT_EQ(d->od().get(0x1017), static_cast<uint32_t>(options.drive_common.heartbeat_period.count()));
    EXPECT_EQ(d->od().get(0x1016, 1),
              (1u << 16) | static_cast<uint32_t>(options.drive_common.master_heartbeat_timeout.count()));
    EXPECT_EQ(d->od().get(0x1600, 0), 2u);
    EXPECT_EQ(d->od().get(0x1600, 2), 0x60FF0020u);
    EXPECT_EQ(d->od().get(0x1A00, 2), 0x60640020u);
    EXPECT_EQ(d->od().get(0x1A01, 1), 0x606C0020u);
  }
  EXPECT_EQ(trans->od().get(0x6083), 146000u);
  EXPECT_EQ(trans->od().get(0x6085), 4u * 146000u);
  run(100ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kStopped);
  EXPECT_EQ(ctl->odometry().reason, "no command yet");
  EXPECT_GT(ctl->odometry().samples, 5u);
}

TEST_F(BaseSim, VelocityCommandDrivesBothAxesWithinLimits)
{
  bring_up();
  drive(0.5, -0.8);
  // Acceleration limit: 1 m/s^2 -> at most ~0.25 m/s after 0.25 s.
  run(250ms);
  EXPECT_LE(trans_velocity(), 0.25 + 0.02);
  EXPECT_GT(trans_velocity(), 0.15);
  run(1000ms);
  EXPECT_NEAR(trans_velocity(), 0.5, 1e-4);
  EXPECT_NEAR(rot_velocity(), -0.8, 1e-4);
  const BaseOdometry& o = ctl->odometry();
  EXPECT_EQ(o.status, BaseStatus::kOk);
  EXPECT_NEAR(o.v, 0.5, 1e-4);
  EXPECT_NEAR(o.omega, -0.8, 1e-4);
  // Beyond the limits: clamped to 1 m/s and 2.5 rad/s.
  drive(3.0, 9.0);
  run(2000ms);
  EXPECT_NEAR(trans_velocity(), 1.0, 1e-4);
  EXPECT_NEAR(rot_velocity(), 2.5, 1e-4);
}

TEST_F(BaseSim, OdometryFollowsAnAnalyticArc)
{
  // Equal ramps in units (a_v / a_omega = v / omega) keep the curvature constant during
  // acceleration and braking, so the whole path is one circle of radius v / omega = 1 m.
  BaseDriverOptions o = shipped_options();
  o.translation.max_acceleration = 0.6;
  o.rotation.max_acceleration = 0.6;
  o.rotation.quick_stop_deceleration = 4.0;
  build(o);
  bring_up();
  drive(0.3, 0.3);
  run(4000ms);
  refresh_command = false;  // deadman: controlled stop on the same ramps
  run(1000ms);
  ASSERT_EQ(trans->actual_velocity(), 0.0);
  const BaseOdometry& odo = ctl->odometry();
  const double R = 1.0;
  const double th = rot->actual_position() / o.rotation.counts_per_unit;  // the steering angle
  const double s = trans->actual_position() / o.translation.counts_per_unit;
  EXPECT_NEAR(odo.pose.theta, std::remainder(th, 2 * M_PI), 1e-4);
  EXPECT_NEAR(odo.distance, s, 1e-4);
  EXPECT_NEAR(s, R * th, 2e-3) << "the drives kept v/omega constant";
  EXPECT_NEAR(odo.pose.x, R * std::sin(th), 2e-3);
  EXPECT_NEAR(odo.pose.y, R * (1 - std::cos(th)), 2e-3);
  std::printf("[ figures  ] arc: s=%.4f m theta=%.4f rad, odometry (%.5f, %.5f) vs circle (%.5f, %.5f)\n", s, th,
              odo.pose.x, odo.pose.y, R * std::sin(th), R * (1 - std::cos(th)));
}

TEST_F(BaseSim, DeadmanStopsBothDrivesWhenCommandsGoStale)
{
  bring_up();
  drive(0.6, 0.5);
  run(1500ms);
  ASSERT_EQ(ctl->odometry().status, BaseStatus::kOk);
  // Last command now; configured deadline 150 ms (the message's 500 ms cannot extend it).
  refresh_command = false;
  ctl->command(cmd, bus->now(), 500ms);
  const auto sent = bus->now();
  auto t = run_until([this] { return trans->target_velocity() == 0 && rot->target_velocity() == 0; }, 1000ms);
  ASSERT_TRUE(t);
  EXPECT_GE(*t, 150ms);
  EXPECT_LE(*t, 150ms + options.master.sync_period + 2ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kStopped);
  EXPECT_EQ(ctl->odometry().reason, "command stale (deadman)");
  // Controlled stop on the profile deceleration (1 m/s^2): 0.6 m/s -> 0 in ~0.6 s, not a quick stop.
  run(300ms);
  EXPECT_GT(trans_velocity(), 0.2);
  auto stopped = run_until([this] { return trans->actual_velocity() == 0 && rot->actual_velocity() == 0; }, 1000ms);
  ASSERT_TRUE(stopped);
  EXPECT_EQ(trans->power_state(), PowerState::kOperationEnabled) << "a deadman stop keeps the drives enabled";
  // A message deadline shorter than the configured one wins.
  ctl->command({0.3, 0.0}, bus->now(), 40ms);
  run(20ms);
  EXPECT_NE(trans->target_velocity(), 0);
  t = run_until([this] { return trans->target_velocity() == 0; }, 500ms);
  ASSERT_TRUE(t);
  EXPECT_LE(*t, 40ms - 20ms + options.master.sync_period + 2ms);
  (void)sent;
}

TEST_F(BaseSim, LossOfTheRotationNodeStopsTheRobotWithinItsConsumerTimeAndARamp)
{
  bring_up();
  drive(0.4, 0.2);
  run(1500ms);
  ASSERT_NEAR(trans_velocity(), 0.4, 1e-4);
  // Worst case for detection: the cable is cut right after the node's heartbeat went out.
  const canid_t rot_heartbeat = 0x700 + options.rotation.node_id;
  bus->clear_log();
  ASSERT_TRUE(run_until([&] { return !bus->log().empty() && frame_id(bus->log().back().second) == rot_heartbeat; }, 100ms));
  bus->set_connected(r_id, false);  // the rotation drive drops off the bus
  auto commanded_zero = run_until([this] { return trans->target_velocity() == 0 || trans->power_state() != PowerState::kOperationEnabled; }, 1000ms);
  ASSERT_TRUE(commanded_zero);
  auto stopped = run_until([this] { return trans->actual_velocity() == 0.0; }, 1000ms);
  ASSERT_TRUE(stopped);
  const auto total = *commanded_zero + *stopped;
  std::printf("[ figures  ] rotation node lost at 0.4 m/s: stop commanded after %lld ms, translation at rest "
              "after %lld ms (simulated)\n",
              static_cast<long long>(commanded_zero->count()), static_cast<long long>(total.count()));
  // The master's consumer time for the drive (120 ms shipped: it rides out stalls of a loaded
  // machine), then the quick-stop ramp (0.1 s at 4 m/s^2), plus a SYNC cycle for each to act.
  EXPECT_LE(*commanded_zero, options.drive_common.heartbeat_timeout + options.master.sync_period + 2ms);
  EXPECT_LE(total, options.drive_common.heartbeat_timeout + quick_stop_ramp(0.4) + 2 * options.master.sync_period + 2ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kFault);
  EXPECT_NE(ctl->odometry().reason.find("rotation drive 3: heartbeat lost"), std::string::npos)
      << ctl->odometry().reason;
  EXPECT_EQ(ctl->odometry().commanded.v, 0.0);
  // The cut-off drive stopped itself: it lost the master's heartbeat.
  run(200ms);
  EXPECT_TRUE(rot->master_heartbeat_lost());
  EXPECT_EQ(rot->actual_velocity(), 0.0);
  // Cable back: both drives are brought up again, and move on fresh commands.
  bus->set_connected(r_id, true);
  auto back = run_until([this] { return both_enabled(); }, 3000ms);
  ASSERT_TRUE(back) << ctl->odometry().reason;
  run(100ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kOk);
  run(1000ms);
  EXPECT_NEAR(trans_velocity(), 0.4, 1e-4);
}

TEST_F(BaseSim, LossOfTheTranslationNodeStopsItByItsOwnConsumer)
{
  bring_up();
  drive(0.4, 0.5);
  run(1500ms);
  bus->set_connected(t_id, false);
  auto stopped = run_until([this] { return trans->actual_velocity() == 0.0 && rot->actual_velocity() == 0.0; }, 1000ms);
  ASSERT_TRUE(stopped);
  std::printf("[ figures  ] translation node lost at 0.4 m/s: both drives at rest after %lld ms (simulated)\n",
              static_cast<long long>(stopped->count()));
  // The drive's consumer time for the master's heartbeat + 0.1 s quick-stop ramp at 4 m/s^2.
  EXPECT_LE(*stopped, options.drive_common.master_heartbeat_timeout + quick_stop_ramp(0.4) + 2ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kFault);
}

TEST_F(BaseSim, EmcyStopsReportsAndRecoversAfterFaultReset)
{
  bring_up();
  drive(0.5, 0.3);
  run(1500ms);
  trans->inject_fault(canopen::emcy::kContinuousOverCurrent);
  auto reported = run_until([this] { return ctl->odometry().status == BaseStatus::kFault; }, 100ms);
  ASSERT_TRUE(reported);
  EXPECT_NE(ctl->odometry().reason.find("over-current"), std::string::npos) << ctl->odometry().reason;
  auto stopped = run_until([this] { return trans->actual_velocity() == 0.0 && rot->actual_velocity() == 0.0; }, 500ms);
  ASSERT_TRUE(stopped);
  EXPECT_EQ(trans->power_state(), PowerState::kFault);
  // While the cause persists, resets fail and everything stays stopped.
  run(1500ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kFault);
  EXPECT_EQ(trans->power_state(), PowerState::kFault);
  EXPECT_EQ(rot->actual_velocity(), 0.0);
  // Cause gone: the master's next fault reset works, the state machine is re-run.
  trans->clear_fault_condition();
  auto recovered = run_until([this] { return both_enabled(); }, 2000ms);
  ASSERT_TRUE(recovered) << ctl->odometry().reason;
  run(50ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kOk);
  run(1000ms);
  EXPECT_NEAR(trans_velocity(), 0.5, 1e-4);
}

TEST_F(BaseSim, BusOffStopsTheRobotAndRecoversAfterRestart)
{
  bring_up();
  drive(0.4, 0.0);
  run(1500ms);
  bus->inject(ctl_id, make_error_frame(CAN_ERR_BUSOFF));
  run(1ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kFault);
  EXPECT_EQ(ctl->odometry().reason, "CAN bus-off");
  // The master is silent; the drives stop on their heartbeat consumers.
  auto stopped = run_until([this] { return trans->actual_velocity() == 0.0; }, 1000ms);
  ASSERT_TRUE(stopped);
  EXPECT_LE(*stopped, options.drive_common.master_heartbeat_timeout + quick_stop_ramp(0.4) + 2ms);
  run(300ms);
  bus->inject(ctl_id, make_error_frame(CAN_ERR_RESTARTED));
  auto back = run_until([this] { return both_enabled(); }, 3000ms);
  ASSERT_TRUE(back) << ctl->odometry().reason;
  run(1000ms);
  EXPECT_NEAR(trans_velocity(), 0.4, 1e-4);
}

TEST_F(BaseSim, RebootedDriveIsReconfiguredWithoutAnOdometryJump)
{
  bring_up();
  drive(0.3, 0.0);
  run(1500ms);
  refresh_command = false;
  run(1000ms);
  const double x_before = ctl->odometry().pose.x;
  ASSERT_GT(x_before, 0.2);
  trans->power_off();
  run(200ms);
  EXPECT_EQ(ctl->odometry().status, BaseStatus::kFault);
  trans->power_on(bus->now());  // boots with its counter wherever it is
  auto back = run_until([this] { return both_enabled(); }, 3000ms);
  ASSERT_TRUE(back) << ctl->odometry().reason;
  run(100ms);
  EXPECT_NEAR(ctl->odometry().pose.x, x_before, 1e-6);
}

TEST_F(BaseSim, DriveBackFromAHeartbeatOutageKeepsItsMotionInTheOdometry)
{
  // The drive does not reboot (a stalled master, a bus hiccup longer than the consumer time):
  // it goes on counting, so the motion during the outage and the reconfiguration belongs in the
  // odometry. Re-baselining there lost 3-10 cm per outage in the demo, along the hallway axis
  // where the scan mapper trusts odometry.
  bring_up();
  drive(0.4, 0.0);
  run(1500ms);
  auto odometry_error = [this] {
    return ctl->odometry().distance - trans->actual_position() / options.translation.counts_per_unit;
  };
  const double error_before = odometry_error();
  bus->set_connected(t_id, false);
  // Beyond the master's consumer time for the drive, before the drive's own for the master.
  ASSERT_LT(options.drive_common.heartbeat_timeout + 10ms, options.drive_common.master_heartbeat_timeout);
  run(options.drive_common.heartbeat_timeout + 10ms);
  bus->set_connected(t_id, true);
  auto back = run_until([this] { return both_enabled(); }, 3000ms);
  ASSERT_TRUE(back) << ctl->odometry().reason;
  run(500ms);
  EXPECT_GT(trans->actual_position() / options.translation.counts_per_unit, 0.3);
  // Re-baselined, the outage here (130 ms, then the reconfiguration) would lose about 5 mm.
  EXPECT_NEAR(odometry_error(), error_before, 1e-3);
}

TEST_F(BaseSim, MissingTpdosAreAFault)
{
  bring_up();
  drive(0.3, 0.0);
  run(1000ms);
  const canid_t tpdo1 = 0x180 + options.translation.node_id;
  bus->set_drop([tpdo1](int, const can_frame& f) { return frame_id(f) == tpdo1; });
  auto fault = run_until([this] { return ctl->odometry().status == BaseStatus::kFault; }, 500ms);
  ASSERT_TRUE(fault);
  EXPECT_NE(ctl->odometry().reason.find("no TPDO"), std::string::npos) << ctl->odometry().reason;
  auto stopped = run_until([this] { return trans->actual_velocity() == 0.0; }, 500ms);
  ASSERT_TRUE(stopped);
  bus->set_drop(nullptr);
  auto back = run_until([this] { return both_enabled(); }, 3000ms);
  ASSERT_TRUE(back) << ctl->odometry().reason;
}

TEST(BaseDriverOptions, ShippedConfigAndValidation)
{
  const BaseDriverOptions o = shipped_options();
  EXPECT_EQ(o.interface, "virtual");
  EXPECT_EQ(o.translation.node_id, 2);
  EXPECT_EQ(o.rotation.node_id, 3);
  EXPECT_EQ(o.command_deadline, 150ms);
  EXPECT_EQ(o.translation.to_counts(1.0), 146000);
  EXPECT_DOUBLE_EQ(o.rotation.to_units(19100), 1.0);
  auto bad = [](const std::string& yaml) {
    auto cfg = config::Config::parse(yaml, "test.yaml");
    load_base_driver_options(cfg);
    cfg.finish();
  };
  EXPECT_THROW(bad("can: {interface: carrier-pigeon}"), config::ConfigError);
  EXPECT_THROW(bad("drives: {rotation: {node_id: 2}}"), config::ConfigError);  // same as translation
  EXPECT_THROW(bad("drives: {heartbeat_period_ms: 100, heartbeat_timeout_ms: 80}"), config::ConfigError);
  EXPECT_THROW(bad("drives: {translation: {max_acceleration: 5, quick_stop_deceleration: 2}}"), config::ConfigError);
  EXPECT_THROW(bad("base: {command_deadline_ms: 5}"), config::ConfigError);
  EXPECT_THROW(bad("base: {comand_deadline_ms: 100}"), config::ConfigError);  // typo: unknown key
  try {
    bad("drives: {translation: {node_id: 300}}");
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("drives.translation.node_id"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(bad("can: {interface: socketcan, socketcan_device: can1}"));
}

}  // namespace
}  // namespace rgnav::can::base
