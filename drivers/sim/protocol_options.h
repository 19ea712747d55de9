// What protocol mode must agree on with the real drivers, read from the drivers' own config
// files (named in config/sim.yaml, section `protocol`), never restated: the LMS port
// (laser_driver.port), the virtual CAN bus socket, the drive node ids, counts per unit and
// signs (base_driver's `can` / `drives` sections, through base_driver's own loader).
#pragma once

#include <string>

#include "config/config.h"
#include "sim/protocol_conversions.h"
#include "sim/sim_options.h"

namespace rgnav::sim {

struct ProtocolOptions
{
  ProtocolSection files;
  std::string laser_port;    // stable path (symlink) of the emulated LMS's pty
  std::string can_bus_path;  // virtual CAN bus socket ('@name': abstract namespace)
  DriveAxes axes;
  // SCHED_FIFO for the in-process bus's thread (0: normal): the stepping thread's priority, set
  // by the process (sim.realtime_priority), since the emulated drives and their bus stall alike.
  int bus_realtime_priority = 0;
};

// Reads the driver configs `files` names. Their own errors name their files; a config the
// simulator cannot serve (a /dev port, a SocketCAN interface) is an error naming
// 'protocol.<key>' of `protocol_section`.
ProtocolOptions load_protocol_options(const ProtocolSection& files, const config::Config& protocol_section,
                                      const config::RobotDescription& robot);

}  // namespace rgnav::sim
