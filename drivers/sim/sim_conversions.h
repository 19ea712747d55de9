// Simulator outputs <-> rgnav messages. SIM_TRUTH is an odometry_t whose odom_from_base is
// the ground-truth pose of the base in the WORLD frame (the world file's frame), v/omega the
// true velocities and distance the true path length; status is STATUS_SIMULATED.
#pragma once

#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "sim/simulator.h"

namespace rgnav::sim {

laser_scan_t to_laser_scan_msg(const LaserScan& scan);
odometry_t to_odometry_msg(const OdometrySample& sample);
odometry_t to_truth_msg(const OdometrySample& sample);
DriveCommand to_drive_command(const velocity_cmd_t& cmd);

}  // namespace rgnav::sim
