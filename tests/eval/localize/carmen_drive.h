// A drive written for MRPT's pf-localization, run beside rgnav's localizer on the same data
// (deploy/bench/mrpt/README.md has the folder contract): the odometry and scans as a CARMEN log
// in the log's own times, the true pose in the map frame of the occupancy grid, and the start.
#pragma once

#include <fstream>
#include <string>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"

namespace rgnav::localize_eval {

class CarmenDrive
{
 public:
  // Creates DIR (and its parents); every `scan_every`-th scan is written.
  CarmenDrive(const std::string& dir, const geometry::Pose2& base_from_laser, int scan_every);
  void odometry(int64_t utime, const geometry::Pose2& odom_from_base, double v, double omega);
  // truth_in_grid: nullptr when the true pose lies in no region (not scored).
  void scan(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base, const geometry::Pose2* truth_in_grid);
  void start(const std::string& mode, const geometry::Pose2& truth_in_grid);

 private:
  std::string dir_;
  geometry::Pose2 base_from_laser_;
  int scan_every_;
  int64_t scans_ = 0;
  std::ofstream log_, truth_;
};

}  // namespace rgnav::localize_eval
