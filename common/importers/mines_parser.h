// The Mines ParisTech log format (CoreSLAM / BreezySLAM exp1.dat, exp2.dat): one line per scan,
//   timestamp[us] flag left_ticks right_ticks <20 more fields> <Hokuyo URG-04LX ranges in mm>
// Odometry is integrated from the wheel ticks with the robot of BreezySLAM's Mines setup
// (examples/mines.py: wheel radius 77 mm, half axle 165 mm, 2000 ticks per wheel turn; laser
// 240 deg, 70 unusable beams at each end).
#pragma once

#include <string>

#include "importers/log_records.h"

namespace rgnav::importers {

struct MinesOptions
{
  double wheel_radius_m = 0.077;
  double half_axle_m = 0.165;
  double ticks_per_turn = 2000.0;
  int first_range_field = 24;      // 0-based index of the first range
  double angle_increment_deg = 360.0 / 1024.0;  // URG-04LX step
  int margin_beams = 70;           // beams at each end that see the robot (set invalid)
  float range_min_m = 0.02f;       // URG readings below 20 mm are error codes
  float range_max_m = 5.6f;        // URG-04LX maximum
};

ImportedLog read_mines(const std::string& path, const MinesOptions& options = {});

}  // namespace rgnav::importers
