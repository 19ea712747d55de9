#include "sim/sim_options.h"

#include <filesystem>

#include "config/duration_fields.h"

namespace rgnav::sim {

SimulatorOptions load_simulator_options(const config::Config& cfg, const config::RobotDescription& described)
{
  SimulatorOptions o;
  const auto sim = cfg.section("sim");
  o.seed = static_cast<uint64_t>(sim.integer("seed", 1, 0, INT64_MAX));
  o.physics_step = std::chrono::microseconds(sim.integer("physics_step_us", o.physics_step.count(), 100, 20000));
  o.odometry_hz = sim.number("odometry_hz", o.odometry_hz, 1.0, 1000.0);
  o.laser_enabled = sim.boolean("laser_enabled", o.laser_enabled);

  const auto robot = cfg.section("robot");
  o.robot.radius = described.radius;
  o.robot.height = robot.number("height", o.robot.height, 0.1, 3.0);
  o.robot.ground_clearance = robot.number("ground_clearance", o.robot.ground_clearance, 0.0, 0.5);
  if (o.robot.ground_clearance >= o.robot.height) robot.fail("ground_clearance", "must be below height");

  const auto drive = cfg.section("drive");
  o.drive.v_max = drive.number("v_max", o.drive.v_max, 0.01, 5.0);
  o.drive.omega_max = drive.number("omega_max", o.drive.omega_max, 0.01, 10.0);
  o.drive.accel = drive.number("accel", o.drive.accel, 0.01, 20.0);
  o.drive.brake_decel = drive.number("brake_decel", o.drive.brake_decel, 0.01, 20.0);
  if (o.drive.brake_decel < o.drive.accel) drive.fail("brake_decel", "a body brakes at least as hard as it accelerates");
  o.drive.alpha = drive.number("alpha", o.drive.alpha, 0.01, 50.0);

  const auto odo = cfg.section("odometry");
  o.odometry.scale_translation = odo.number("scale_translation", 0.0, -0.5, 0.5);
  o.odometry.scale_rotation = odo.number("scale_rotation", 0.0, -0.5, 0.5);
  o.odometry.bias_rotation_per_m = odo.number("bias_rotation_per_m", 0.0, -1.0, 1.0);
  o.odometry.sigma_translation = odo.number("sigma_translation", 0.0, 0.0, 1.0);
  o.odometry.sigma_rotation = odo.number("sigma_rotation", 0.0, 0.0, 1.0);
  o.odometry.sigma_rotation_per_m = odo.number("sigma_rotation_per_m", 0.0, 0.0, 1.0);

  const auto laser = cfg.section("laser");
  o.laser.sensor = laser.string("sensor", o.laser.sensor);
  if (o.laser.sensor.empty()) laser.fail("sensor", "must not be empty");
  o.laser.beams = static_cast<int>(laser.integer("beams", o.laser.beams, 181, 361));
  if (o.laser.beams != 181 && o.laser.beams != 361) laser.fail("beams", "an LMS 2xx gives 181 or 361 beams over 180 deg");
  o.laser.range_mode_m = static_cast<int>(laser.integer("range_mode_m", o.laser.range_mode_m, 8, 80));
  if (o.laser.range_mode_m != 8 && o.laser.range_mode_m != 80) laser.fail("range_mode_m", "must be 8 (mm) or 80 (cm)");
  o.laser.noise_sigma = laser.number("noise_sigma", o.laser.noise_sigma, 0.0, 1.0);
  const auto& mount = described.laser_front.base_from_laser;
  o.laser.mount_x = mount.x();
  o.laser.mount_y = mount.y();
  o.laser.mount_yaw = mount.theta();
  o.laser.mount_height = described.laser_front.height;
  return o;
}

ProcessOptions load_process_options(const config::Config& sim)
{
  ProcessOptions p;
  p.world = sim.required_string("world");
  p.interface = sim.choice("interface", "direct", {"direct", "protocol"}) == "direct" ? InterfaceMode::kDirect
                                                                                     : InterfaceMode::kProtocol;
  p.clock = sim.choice("clock", "realtime", {"realtime", "fast"}) == "realtime" ? ClockMode::kRealtime : ClockMode::kFast;
  p.time_scale = sim.number("time_scale", p.time_scale, 0.01, 100.0);
  p.fast_chunk = std::chrono::microseconds(sim.integer("fast_chunk_us", p.fast_chunk.count(), 100, 1'000'000));
  p.tick = config::milliseconds(sim, "tick_ms", p.tick, 1, 100);
  p.realtime_priority = static_cast<int>(sim.integer("realtime_priority", p.realtime_priority, 0, 99));
  return p;
}

ProtocolSection load_protocol_section(const config::Config& protocol, const std::string& config_dir)
{
  auto resolve = [&config_dir](const std::string& path) {
    const std::filesystem::path p(path);
    return p.is_absolute() || config_dir.empty() ? p.string() : (std::filesystem::path(config_dir) / p).string();
  };
  ProtocolSection s;
  s.laser_driver_config = resolve(protocol.string("laser_driver_config", "laser_driver_sim.yaml"));
  s.base_driver_config = resolve(protocol.string("base_driver_config", "base_driver_sim.yaml"));
  s.internal_broker = protocol.choice("can_broker", "internal", {"internal", "external"}) == "internal";
  return s;
}

void check_protocol_clock(const ProcessOptions& process, const config::Config& sim)
{
  if (process.interface != InterfaceMode::kProtocol) return;
  if (process.clock != ClockMode::kRealtime)
    sim.fail("clock", "protocol mode needs 'realtime': the real drivers time the serial line and the CAN bus by the wall clock");
  if (process.time_scale != 1.0) sim.fail("time_scale", "protocol mode needs 1.0: the real drivers run on the wall clock");
}

}  // namespace rgnav::sim
