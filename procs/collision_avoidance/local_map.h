// The local obstacle map collision avoidance reasons on: obstacle points in the odometry
// frame from the last few laser scans (each placed with the odometry pose at its time) and
// the occupied cells of the newest OBSTACLES_3D grid, in a uniform hash grid for fast
// "how far is the nearest obstacle from here?" queries. Points older than `max_age` or
// farther than `max_range` from the robot are dropped.
#pragma once

#include <Eigen/Core>

#include <deque>
#include <unordered_map>
#include <vector>

#include "geometry/pose2.h"
#include "time/message_time.h"

namespace rgnav::collision_avoidance {

using geometry::Pose2;

struct LocalMapOptions
{
  int max_scans = 5;          // scans kept
  double max_age = 1.0;       // [s] older scans are dropped
  double max_range = 6.0;     // [m] farther readings are ignored
  double cell = 0.10;         // [m] hash grid pitch
  int grid_occupied_min = 50; // [%] obstacle grid cells at least this occupied are obstacles
};

// A scan's obstacle readings in the robot's base frame.
struct ScanPoints
{
  time::Time stamp{};
  Pose2 odom_from_base;                 // pose at the scan's time
  std::vector<Eigen::Vector2d> points;  // base frame
};

class LocalMap
{
 public:
  explicit LocalMap(const LocalMapOptions& options) : options_(options) {}

  void add_scan(ScanPoints scan);
  // Replaces the 3D-derived obstacles (points in the odom frame).
  void set_grid_points(time::Time stamp, std::vector<Eigen::Vector2d> odom_points);
  // Drops what is too old at `now` and rebuilds the index.
  void rebuild(time::Time now);

  // Distance from p (odom frame) to the nearest obstacle point, searching up to `radius`
  // (infinity if none).
  double clearance(const Eigen::Vector2d& p, double radius) const;
  size_t size() const { return points_.size(); }
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  int64_t key(int ix, int iy) const { return (static_cast<int64_t>(ix) << 32) ^ static_cast<uint32_t>(iy); }

  const LocalMapOptions options_;
  std::deque<ScanPoints> scans_;
  time::Time grid_stamp_{};
  std::vector<Eigen::Vector2d> grid_points_;
  std::vector<Eigen::Vector2d> points_;  // odom frame, all sources
  std::unordered_map<int64_t, std::vector<uint32_t>> index_;
};

}  // namespace rgnav::collision_avoidance
