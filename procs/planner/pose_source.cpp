#include "planner/pose_source.h"

#include "time/units.h"

namespace rgnav::planner {

namespace {
using time::kUs;
}

const PoseSource::Fix* PoseSource::preferred(int64_t utime) const
{
  if (localized_ && static_cast<double>(utime - localized_->pose.utime) * kUs <= options_.fresh_s) return &*localized_;
  if (slam_ && (!localized_ || slam_->pose.utime > localized_->pose.utime)) return &*slam_;
  return localized_ ? &*localized_ : nullptr;
}

std::optional<RobotPose> PoseSource::localized(const RobotPose& fix)
{
  if (localized_ && fix.utime < localized_->pose.utime) return std::nullopt;
  localized_ = Fix{fix, epoch_};
  return fix;
}

std::optional<RobotPose> PoseSource::slam(const RobotPose& fix)
{
  if (slam_ && fix.utime < slam_->pose.utime) return std::nullopt;
  slam_ = Fix{fix, epoch_};
  if (preferred(fix.utime) != &*slam_) return std::nullopt;
  return fix;
}

std::optional<RobotPose> PoseSource::odometry(int64_t utime, const geometry::Pose2& odom_from_base)
{
  const Fix* f = preferred(utime);
  if (!f || f->epoch != epoch_ || utime < f->pose.utime) return std::nullopt;
  const geometry::Pose2 moved = f->pose.odom_from_base.between(odom_from_base);
  if (moved.translation().norm() > options_.max_carry_m) return std::nullopt;
  RobotPose p = f->pose;
  p.utime = utime;
  p.region_from_base = f->pose.region_from_base * moved;
  p.odom_from_base = odom_from_base;
  return p;
}

}  // namespace rgnav::planner
