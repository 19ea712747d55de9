// Protocol mode, in process: unit conversions between drive counts and simulator units, the
// encoders reporting the odometry model (errors included), and the simulated-time loop of
// the real CANopen master (base_driver's SynchroDriveController) against ProtocolDrives in
// the simulator's physics step.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>

#include "box_world.h"
#include "can/base_driver/synchro_drive_controller.h"
#include "config/config.h"
#include "sim/protocol_drives.h"
#include "sim/protocol_options.h"
#include "source_paths.h"

namespace rgnav::sim {
namespace {

using namespace std::chrono_literals;
using can::base::AxisOptions;

using testing::config_path;

can::base::BaseDriverOptions shipped_sim_base_options()
{
  return can::base::load_base_driver_options(config::Config::load(config_path("base_driver_sim.yaml")));
}

DriveAxes shipped_axes()
{
  const auto b = shipped_sim_base_options();
  return {b.translation, b.rotation};
}

using rgnav::testing::box_world;

// Odometry errors chosen so their effect is unmistakable and free of noise.
SimulatorOptions systematic_error_options()
{
  SimulatorOptions o;
  o.laser_enabled = false;
  o.odometry.scale_translation = 0.05;
  o.odometry.scale_rotation = -0.1;
  o.odometry.bias_rotation_per_m = 0.02;
  return o;
}

TEST(ProtocolConversions, CountsAndUnitsRoundTripWithTheDriveSign)
{
  AxisOptions a;
  a.counts_per_unit = 146000.0;
  a.sign = 1;
  EXPECT_DOUBLE_EQ(counts_to_units(73000.0, a), 0.5);
  EXPECT_DOUBLE_EQ(units_to_counts(0.5, a), 73000.0);
  a.sign = -1;
  EXPECT_DOUBLE_EQ(counts_to_units(73000.0, a), -0.5);
  for (double u : {-1.3, -0.001, 0.0, 0.25, 2.0}) EXPECT_NEAR(counts_to_units(units_to_counts(u, a), a), u, 1e-12);
  // The same scale base_driver applies (its integer conversion rounds to whole counts).
  EXPECT_EQ(a.to_counts(0.5), static_cast<int32_t>(units_to_counts(0.5, a)));
  EXPECT_NEAR(a.to_units(-73000), counts_to_units(-73000.0, a), 1e-12);
}

TEST(ProtocolConversions, DemandsBecomeTheSynchroDriveCommand)
{
  const DriveAxes axes = shipped_axes();
  const DriveCommand c = command_from_demands(0.4 * axes.translation.counts_per_unit * axes.translation.sign,
                                              -0.7 * axes.rotation.counts_per_unit * axes.rotation.sign, axes);
  EXPECT_NEAR(c.v, 0.4, 1e-12);
  EXPECT_NEAR(c.omega, -0.7, 1e-12);
}

TEST(ProtocolConversions, EncodersCountTheOdometryModelNotTheTruth)
{
  Simulator sim(box_world(10.0), systematic_error_options());
  TimedCommandSource cmd;
  cmd.set(sim.now_utime(), {0.5, 0.3}, 10'000'000);
  sim.set_command_source(&cmd);
  const StepOutput out = sim.step(2s);
  ASSERT_FALSE(out.odometry.empty());
  const double true_distance = out.odometry.back().true_distance;
  DriveAxes axes = shipped_axes();
  axes.rotation.sign = -1;  // an inverted drive counts the other way
  const EncoderReadings r = encoder_readings(sim, axes);
  EXPECT_NEAR(r.translation.position, sim.odometry().translation_total() * axes.translation.counts_per_unit, 1e-6);
  EXPECT_NEAR(r.rotation.position, -sim.odometry().rotation_total() * axes.rotation.counts_per_unit, 1e-6);
  // The measured totals carry the systematic errors: +5 % distance, -10 % turn + 0.02 rad/m.
  EXPECT_GT(true_distance, 0.5);
  EXPECT_NEAR(counts_to_units(r.translation.position, axes.translation), 1.05 * true_distance, 1e-9);
  EXPECT_NEAR(r.translation.velocity, 1.05 * sim.drive().v() * axes.translation.counts_per_unit, 1e-6);
  EXPECT_NEAR(r.rotation.velocity,
              -(0.9 * sim.drive().omega() + 0.02 * std::fabs(sim.drive().v())) * axes.rotation.counts_per_unit, 1e-6);
}

// Controller, drives and simulator on one simulated clock; frames are delivered at once.
class MasterAgainstSimulator : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    base = shipped_sim_base_options();
    sim = std::make_unique<Simulator>(box_world(30.0), systematic_error_options());
    ctl = std::make_unique<can::base::SynchroDriveController>(base, [this](const can_frame& f) { queue.push_back({0, f}); });
    drives = std::make_unique<ProtocolDrives>(DriveAxes{base.translation, base.rotation},
                                              [this](const can_frame& f) { queue.push_back({1, f}); },
                                              [this](const can_frame& f) { queue.push_back({2, f}); });
    drives->power_on(sim->now_utime());
    sim->set_command_source(drives.get());
  }
  // Every frame reaches every endpoint but its sender (a CAN bus).
  void deliver()
  {
    const int64_t now = sim->now_utime();
    while (!queue.empty()) {
      const auto [from, f] = queue.front();
      queue.pop_front();
      if (from != 0) ctl->handle(f, emulator_time(now));
      if (from != 1) drives->handle_translation(f, now);
      if (from != 2) drives->handle_rotation(f, now);
    }
  }
  // One physics step, as ProtocolHardware::advance does it (plus the master's side).
  void step()
  {
    const int64_t now = sim->now_utime();
    if (command && now >= next_command_us) {
      ctl->command(*command, emulator_time(now), 300ms);
      next_command_us = now + 50'000;
    }
    ctl->tick(emulator_time(now));
    deliver();
    drives->tick(now);
    deliver();
    const StepOutput out = sim->step(1ms);
    drives->report(*sim);
    for (const auto& s : out.odometry) last_truth = s;
  }
  void run(std::chrono::milliseconds d)
  {
    for (auto t = 0ms; t < d; t += 1ms) step();
  }

  can::base::BaseDriverOptions base;
  std::unique_ptr<Simulator> sim;
  std::unique_ptr<can::base::SynchroDriveController> ctl;
  std::unique_ptr<ProtocolDrives> drives;
  std::deque<std::pair<int, can_frame>> queue;
  std::optional<can::base::VelocityCommand> command;
  int64_t next_command_us = 0;
  OdometrySample last_truth;
};

TEST_F(MasterAgainstSimulator, CommandsMoveTheSimulatedBaseAndOdometryCarriesItsErrors)
{
  run(1500ms);  // bring-up: NMT, SDO configuration, 402 state machine
  ASSERT_EQ(drives->translation().power_state(), can::canopen::cia402::PowerState::kOperationEnabled);
  ASSERT_EQ(drives->rotation().power_state(), can::canopen::cia402::PowerState::kOperationEnabled);
  EXPECT_EQ(sim->truth().x, 0.0) << "no command yet: the base stands still";

  // Straight ahead at 0.5 m/s for 3 s: the truth moves, base_driver's odometry = the
  // simulator's odometry model (5 % long, turning 0.02 rad per m), not the truth.
  command = can::base::VelocityCommand{0.5, 0.0};
  run(3000ms);
  EXPECT_NEAR(sim->drive().v(), 0.5, 1e-6);
  EXPECT_NEAR(ctl->odometry().v, 0.5 * 1.05, 0.002);
  // While moving the master's odometry is up to one SYNC period (10 ms) old.
  EXPECT_NEAR(ctl->odometry().distance, sim->odometry().distance(), 0.5 * 1.05 * 0.010 + 0.001);
  command.reset();
  run(1500ms);  // deadman: the drives stop (controlled), the base stands still
  ASSERT_EQ(sim->drive().v(), 0.0);
  EXPECT_GT(sim->truth().x, 1.0);
  // At standstill the master's odometry is the simulator's, to a few encoder counts.
  EXPECT_NEAR(ctl->odometry().distance, sim->odometry().distance(), 1e-4);
  EXPECT_NEAR(ctl->odometry().pose.x, sim->odometry().pose().x, 1e-4);
  EXPECT_NEAR(ctl->odometry().pose.y, sim->odometry().pose().y, 1e-4);
  EXPECT_NEAR(ctl->odometry().pose.theta, sim->odometry().pose().theta, 1e-4);
  EXPECT_NEAR(ctl->odometry().distance / last_truth.true_distance, 1.05, 1e-3);
  EXPECT_NEAR(ctl->odometry().pose.theta, 0.02 * last_truth.true_distance, 1e-3) << "heading bias per metre";

  // Turn in place at 0.5 rad/s for 2 s: odometry turns 10 % less than the truth.
  command = can::base::VelocityCommand{0.0, 0.5};
  const double theta0_true = sim->truth().theta;
  const double theta0_odo = ctl->odometry().pose.theta;
  run(2000ms);
  command.reset();
  run(1500ms);
  EXPECT_EQ(sim->drive().omega(), 0.0);
  const double turned_true = normalize_angle(sim->truth().theta - theta0_true);
  const double turned_odo = normalize_angle(ctl->odometry().pose.theta - theta0_odo);
  EXPECT_GT(turned_true, 0.7);
  EXPECT_NEAR(turned_odo / turned_true, 0.9, 1e-3);
  EXPECT_NEAR(ctl->odometry().pose.theta, sim->odometry().pose().theta, 1e-4);
  EXPECT_EQ(ctl->odometry().status, can::base::BaseStatus::kStopped);
}

TEST_F(MasterAgainstSimulator, LosingTheMasterStopsTheBase)
{
  run(1500ms);
  command = can::base::VelocityCommand{0.6, 0.0};
  run(2000ms);
  ASSERT_GT(sim->drive().v(), 0.5);
  // The master falls silent (process killed): no heartbeat, no SYNC; the drives' heartbeat
  // consumers quick-stop them, and the simulated base comes to a stop on its own.
  for (int i = 0; i < 2000; ++i) {
    drives->tick(sim->now_utime());
    queue.clear();
    sim->step(1ms);
    drives->report(*sim);
  }
  EXPECT_TRUE(drives->translation().master_heartbeat_lost());
  EXPECT_NEAR(sim->drive().v(), 0.0, 1e-9);
}

}  // namespace
}  // namespace rgnav::sim
