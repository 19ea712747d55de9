// A simulated drive for the localization benchmark: the lock-step simulator follows a route
// (walking people seen by the laser but passed through, as the blind follower cannot avoid
// them), and every scan is handed over with the odometry pose at its time and the true pose.
// A drive can continue another one's odometry (a kidnap: the robot is carried elsewhere, its
// wheel odometry goes on from where it was).
#pragma once

#include <functional>
#include <vector>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"
#include "sim/simulator.h"

namespace rgnav::localize_eval {

struct DriveStep
{
  const sensors::LaserScan& scan;
  geometry::Pose2 odom_from_base;   // at the scan's time
  geometry::Pose2 world_from_base;  // truth at the scan's time
  double true_distance = 0;         // [m] driven since the drive started
  double time_s = 0;                // since the drive started
};

struct OdometryStep
{
  int64_t utime = 0;
  geometry::Pose2 odom_from_base;
  double v = 0, omega = 0;
};

struct DriveSpec
{
  std::vector<sim::Vec2> route;     // first point = start position
  double start_heading = 0;         // [rad]
  double max_s = 60;                // [s] the drive ends here or at the end of the route
  int64_t start_utime = 0;          // message time of the drive's start
  geometry::Pose2 odom_offset;      // odometry continues from this pose (identity: a fresh start)
  uint64_t seed = 1;
};

struct DriveResult
{
  double seconds = 0, distance = 0;
  int64_t end_utime = 0;
  geometry::Pose2 end_odom;         // odometry at the end (the next drive of a kidnap goes on from it)
};

// Runs the drive; on_scan for every scan, on_odometry for every odometry sample (both in time order).
DriveResult run_drive(sim::World world, sim::SimulatorOptions options, const DriveSpec& spec,
                      const std::function<void(const DriveStep&)>& on_scan,
                      const std::function<void(const OdometryStep&)>& on_odometry = nullptr);

// The route from a point part way along `tour` (segment k, fraction s), round the closed tour
// and on, at least `length` metres long.
std::vector<sim::Vec2> route_from(const std::vector<sim::Vec2>& tour, size_t k, double s, double length);

}  // namespace rgnav::localize_eval
