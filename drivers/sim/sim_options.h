// Loading the simulator's options from config/sim.yaml (sections robot, drive, odometry,
// laser, sim) and the robot description (radius, laser mounting). Every key is validated;
// out-of-range values name file and key.
#pragma once

#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "sim/simulator.h"

namespace rgnav::sim {

enum class ClockMode { kRealtime, kFast };
enum class InterfaceMode { kDirect, kProtocol };

// What the rgnav_sim process does with the simulator (section `sim`).
struct ProcessOptions
{
  std::string world;              // world name under <config dir>/worlds, or a path
  InterfaceMode interface = InterfaceMode::kDirect;
  ClockMode clock = ClockMode::kRealtime;
  double time_scale = 1.0;        // realtime: simulated seconds per wall second
  std::chrono::microseconds fast_chunk{13333};  // fast: simulated time per loop turn
  std::chrono::milliseconds tick{2};            // realtime: wall period of the stepping timer
  // realtime: SCHED_FIFO for the stepping thread and the in-process CAN bus when permitted (0:
  // normal). The emulated drives' CAN heartbeats come from them, watched by base_driver to
  // drives.heartbeat_timeout_ms.
  int realtime_priority = 30;
};

// Section `protocol`: where protocol mode finds the configs of the drivers it serves (what
// it reads from them: protocol_options.h).
struct ProtocolSection
{
  std::string laser_driver_config;  // path; relative paths are resolved against the config dir
  std::string base_driver_config;
  bool internal_broker = true;      // run the virtual CAN bus in rgnav_sim (else: vcan_broker)
};

// The footprint radius and the laser mounting pose and height are the robot description's.
SimulatorOptions load_simulator_options(const config::Config& cfg, const config::RobotDescription& robot);
ProcessOptions load_process_options(const config::Config& sim_section);
ProtocolSection load_protocol_section(const config::Config& protocol_section, const std::string& config_dir);
// Protocol mode runs the real drivers on the wall clock (serial line, CAN timing, deadman), so
// the simulation must run in real time at scale 1; throws ConfigError naming `sim.<key>`.
void check_protocol_clock(const ProcessOptions& process, const config::Config& sim_section);

}  // namespace rgnav::sim
