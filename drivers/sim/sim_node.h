// Node adapter of rgnav_sim. Direct mode: BASE_CMD in (held until its deadline, then the
// drive decelerates to a stop), LASER_FRONT / ODOMETRY / SIM_TRUTH out, stepping the
// simulator against wall time (realtime, optionally scaled) or as fast as the loop turns.
// Protocol mode (a HardwareEmulation given): the emulated hardware steps the simulator and
// the real drivers publish LASER_FRONT / ODOMETRY from it; this node publishes SIM_TRUTH only,
// takes no BASE_CMD, and keeps simulated message time on the wall clock.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "config/config.h"
#include "rgnav/velocity_cmd_t.hpp"
#include "runtime/node.h"
#include "sim/hardware_emulation.h"
#include "sim/sim_options.h"
#include "sim/simulator.h"

namespace rgnav::sim {

struct SimChannels
{
  std::string laser = "LASER_FRONT";
  std::string odometry = "ODOMETRY";
  std::string truth = "SIM_TRUTH";
  std::string command = "BASE_CMD";
};

SimChannels load_channels(const config::Config& channels);

class SimNode
{
 public:
  // Registers the BASE_CMD subscription (direct mode) and, unless `manual` (tests), the
  // stepping timer. `make_hardware` (protocol mode) builds the emulation around the simulator.
  using HardwareFactory = std::function<std::unique_ptr<HardwareEmulation>(Simulator&)>;
  SimNode(runtime::Node& node, std::unique_ptr<Simulator> sim, const ProcessOptions& options,
          const SimChannels& channels, bool manual = false, const HardwareFactory& make_hardware = nullptr);

  // Advances simulated time by dt and publishes everything produced meanwhile.
  void advance(std::chrono::microseconds dt);
  const Simulator& simulator() const { return *sim_; }

 private:
  void on_command(const velocity_cmd_t& cmd);
  void on_tick();

  runtime::Node& node_;
  std::unique_ptr<Simulator> sim_;
  std::unique_ptr<HardwareEmulation> hardware_;  // after sim_: destroyed first, it uses sim_
  const ProcessOptions options_;
  const SimChannels channels_;
  TimedCommandSource commands_;
  std::chrono::steady_clock::time_point wall_start_;
  int64_t last_collision_us_ = -1;
};

}  // namespace rgnav::sim
