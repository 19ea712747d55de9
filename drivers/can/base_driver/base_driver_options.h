// Options of the B21r base driver (BaseDriver / SynchroDriveController), loaded and validated
// from config/base_driver.yaml (sections `can`, `drives`, `base`). SI units here; conversion
// to drive units (counts, counts/s, counts/s^2) is done once, by the axis scaling.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "config/config.h"
#include "master/canopen_master.h"
#include "master/drive_master.h"

namespace rgnav::can::base {

// One drive of the synchro drive. Units: m (translation) or rad (rotation).
struct AxisOptions
{
  uint8_t node_id = 2;
  double counts_per_unit = 100000.0;  // encoder counts per m of wheel travel / per rad of steering
  int sign = 1;                       // -1 if the drive counts against the robot's convention
  double max_velocity = 1.0;          // [unit/s] commands are clamped to this
  double max_acceleration = 1.0;      // [unit/s^2] command ramp and the drive's profile ramps
  double quick_stop_deceleration = 4.0;  // [unit/s^2] faults and node loss (0x6085)

  int32_t to_counts(double units) const;  // units or units/s -> counts, sign applied
  double to_units(int64_t counts) const;
  // The master's view of this axis (ramps and limits in counts).
  master::DriveMasterOptions drive_options(const master::DriveMasterOptions& common) const;
};

struct BaseDriverOptions
{
  // Transport.
  std::string interface = "virtual";  // "virtual" (user-space broker) or "socketcan"
  std::string socketcan_device = "can0";
  std::string virtual_bus_path = "/tmp/rgnav-vcan-base.sock";
  std::string virtual_client_name = "base_driver";
  // The CAN thread's scheduling: drive heartbeats are watched to 60 ms (see drives).
  int realtime_priority = 45;  // SCHED_FIFO when permitted (0: normal scheduling)
  bool lock_memory = true;     // mlockall when permitted
  // CANopen master and the drive supervision common to both drives (node id, ramps and
  // limits are per axis).
  master::CanopenMasterOptions master;
  master::DriveMasterOptions drive_common;
  AxisOptions translation{2, 146000.0, 1, 1.0, 1.0, 4.0};
  AxisOptions rotation{3, 19100.0, 1, 2.5, 4.0, 15.0};
  // Deadman: a command is void this long after it arrived (also never later than the
  // command's own deadline).
  std::chrono::milliseconds command_deadline{150};
  // On shutdown: how long to wait for standstill before releasing the drives.
  std::chrono::milliseconds stop_timeout{1000};
};

// Reads `can`, `drives` and `base` of a base_driver config. Throws config::ConfigError.
BaseDriverOptions load_base_driver_options(const config::Config& root);

}  // namespace rgnav::can::base
