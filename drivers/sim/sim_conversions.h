// Simulator outputs <-> rgnav messages (scans convert with common/msg/conversions.h). SIM_TRUTH
// is an odometry_t whose odom_from_base is the ground-truth pose of the base in the WORLD frame
// (the world file's frame), v/omega the true velocities and distance the true path length;
// status is STATUS_SIMULATED.
#pragma once

#include "rgnav/odometry_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "sim/simulator.h"

namespace rgnav::sim {

odometry_t to_odometry_msg(const OdometrySample& sample);
odometry_t to_truth_msg(const OdometrySample& sample);
DriveCommand to_drive_command(const velocity_cmd_t& cmd);

}  // namespace rgnav::sim
