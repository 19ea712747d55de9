// A simple stand-in for the navigation stack in tests and benchmarks: drives a waypoint list
// turning on the spot toward each next waypoint, then straight at it, so the robot stays
// on the polyline a planner checked. Not a controller for the real robot (that is lld).
#pragma once

#include <functional>
#include <vector>

#include "sim/simulator.h"

namespace rgnav::sim {

struct FollowerOptions
{
  double v = 0.6;              // [m/s] cruise speed
  double omega = 1.2;          // [rad/s] turning speed
  double reach = 0.08;         // [m] a waypoint counts as reached within this distance
  double aligned = 0.06;       // [rad] heading error below which the robot drives
};

class WaypointFollower final : public DriveCommandSource
{
 public:
  WaypointFollower(std::vector<Vec2> waypoints, std::function<Pose2()> pose, FollowerOptions options = {})
      : waypoints_(std::move(waypoints)), pose_(std::move(pose)), options_(options)
  {}

  std::optional<DriveCommand> command_at(int64_t utime) override;
  bool done() const { return next_ >= waypoints_.size(); }
  size_t next_index() const { return next_; }

 private:
  std::vector<Vec2> waypoints_;
  std::function<Pose2()> pose_;
  const FollowerOptions options_;
  size_t next_ = 0;
};

}  // namespace rgnav::sim
