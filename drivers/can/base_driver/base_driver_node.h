// Node adapter of base_driver: BASE_CMD (velocity_cmd_t) -> BaseDriver::command, and at a
// fixed rate the driver's odometry -> ODOMETRY (odometry_t); the drive health goes into the
// process heartbeat (DEGRADED with the reason while a fault is active). BASE_CMD has one
// owner (CommandSourceGate): a second source stops the drives and raises an alert (logged,
// and the heartbeat DEGRADED with it) naming both.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "base_driver/base_driver.h"
#include "base_driver/command_source_gate.h"
#include "config/config.h"
#include "rgnav/odometry_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "runtime/node.h"

namespace rgnav::can::base {

struct BaseDriverNodeOptions
{
  std::string base_cmd_channel = "BASE_CMD";
  std::string odometry_channel = "ODOMETRY";
  double odometry_rate_hz = 50.0;
  CommandSourceOptions sources;
};

// Reads `channels`, `base.odometry_rate_hz` and the BASE_CMD owner (`base.command_source`,
// `base.hold_source`, `base.foreign_quiet_ms`).
BaseDriverNodeOptions load_base_driver_node_options(const config::Config& root);

// Message <-> library conversions (pure, round-trip tested).
VelocityCommand to_velocity_command(const velocity_cmd_t& msg);
std::chrono::microseconds command_deadline(const velocity_cmd_t& msg);
odometry_t to_odometry_msg(const BaseOdometry& o, int64_t utime, int64_t seq);

class BaseDriverNode
{
 public:
  // `driver` is started here and stopped by the destructor.
  BaseDriverNode(runtime::Node& node, const BaseDriverNodeOptions& options, std::unique_ptr<BaseDriver> driver);
  ~BaseDriverNode();

 private:
  void publish_odometry();
  void on_command(const velocity_cmd_t& msg);

  runtime::Node& node_;
  BaseDriverNodeOptions options_;
  std::unique_ptr<BaseDriver> driver_;
  CommandSourceGate gate_;
  bool locked_out_ = false;  // as of the last publish_odometry()
  int64_t seq_ = 0;
  int64_t last_utime_ = 0;
  BaseStatus last_status_ = BaseStatus::kStopped;
  std::string last_reason_;
};

}  // namespace rgnav::can::base
