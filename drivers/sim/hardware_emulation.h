// Protocol mode's seam in the simulator process: something that stands in for the robot's
// hardware at the protocol level (ProtocolHardware: an LMS 2xx on a pseudo-terminal and two
// CiA 402 drives on the virtual CAN bus) and therefore steps the simulator itself, so the
// emulated devices see every physics step on the simulator's clock. The real drivers then
// publish LASER_FRONT and ODOMETRY; the simulator node publishes only SIM_TRUTH.
#pragma once

#include <chrono>

#include "sim/simulator.h"

namespace rgnav::sim {

class HardwareEmulation
{
 public:
  virtual ~HardwareEmulation() = default;
  // Advances the simulator it serves by dt and returns what it produced (the emulated laser
  // serves its own scans). That simulator's drive input is the emulation's.
  virtual StepOutput advance(std::chrono::microseconds dt) = 0;
};

}  // namespace rgnav::sim
