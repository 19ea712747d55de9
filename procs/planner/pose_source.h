// Where the robot is, for the planner (no LCM): the localizer's pose in a region while it is
// fresh, else the scan mapper's pose placed in the RG map's current region (while mapping).
// Both come only when the robot has moved (the localizer updates every 0.1 m or 5 deg), so a
// robot standing at its start or waiting at a door would soon have no fresh pose and get no
// targets: between fixes the newest one is carried forward with odometry (exact in the
// odometry frame), for at most max_carry_m of travel (further, the fixes have stopped: the
// localizer is gone, and odometry alone drifts) and never across an odometry restart (a new
// frame: the fix's odometry pose means nothing in it).
#pragma once

#include <cstdint>
#include <optional>

#include "geometry/pose2.h"
#include "planner/planner.h"

namespace rgnav::planner {

struct PoseSourceOptions
{
  double fresh_s = 1.0;        // [s] the localizer's fix is preferred while no older than this
  double max_carry_m = 2.0;    // [m] a fix is carried by odometry at most this far
};

class PoseSource
{
 public:
  explicit PoseSource(const PoseSourceOptions& options) : options_(options) {}

  // A fix of the localizer (region frame + the odometry pose at its time): the pose to hand to
  // the planner now, nullopt if it is older than the one held.
  std::optional<RobotPose> localized(const RobotPose& fix);
  // A fix of the scan mapper, already placed in a region: nullopt while a fresh localizer fix
  // is preferred, or if it is older than the one held.
  std::optional<RobotPose> slam(const RobotPose& fix);
  // Odometry at `utime`: the preferred fix carried forward to it; nullopt when there is none,
  // it is newer than this odometry, it was carried too far, or odometry restarted since.
  std::optional<RobotPose> odometry(int64_t utime, const geometry::Pose2& odom_from_base);
  // The odometry frame changed (a restarted base driver): held fixes are not carried any more.
  void odometry_restarted() { ++epoch_; }

 private:
  struct Fix
  {
    RobotPose pose;
    int64_t epoch = 0;
  };
  // The fix to use at `utime`: the localizer's while fresh, else the newer of the two.
  const Fix* preferred(int64_t utime) const;

  PoseSourceOptions options_;
  std::optional<Fix> localized_;
  std::optional<Fix> slam_;
  int64_t epoch_ = 0;
};

}  // namespace rgnav::planner
