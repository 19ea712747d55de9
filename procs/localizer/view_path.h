// The views the robot has had since its pose became unknown, placed relative to each other by
// odometry. One scan cannot tell apart places that look alike from one spot (the offices along
// a hallway, the wings of a symmetric building); the views of the last few metres together
// can, since the robot's path shows what lies beside and behind it. Global localization claims
// a pose only when no other place explains these views nearly as well (localizer.h).
//
// Views are kept `spacing` metres of travel apart (a turn of 1 rad counts as turn_as_travel m):
// neighbouring scans see the same walls and add little; the newest view is always the current
// scan. Views more than `length` metres of travel back are dropped: odometry drift grows with
// the path (a few centimetres per metre), and beyond a few metres it blurs the views more than
// they help.
#pragma once

#include <Eigen/Core>

#include <deque>
#include <vector>

#include "geometry/pose2.h"
#include "localizer/path_score.h"

namespace rgnav::localizer {

class ViewPath
{
 public:
  ViewPath(double spacing, double length, double turn_as_travel);

  void clear() { views_.clear(); }
  bool empty() const { return views_.empty(); }
  size_t size() const { return views_.size(); }
  // The current scan (base frame end points) at odometry pose odom_from_base.
  void add(const geometry::Pose2& odom_from_base, std::vector<Eigen::Vector2d> points);
  // Every view with its pose in the frame of the robot at odom_now (its newest view's pose), to
  // score a candidate "the robot stands here now" against the whole path (path_score.h). The
  // points stay in their own view's frame; valid while the path is unchanged.
  std::vector<PlacedView> placed(const geometry::Pose2& odom_now) const;

 private:
  struct View
  {
    geometry::Pose2 odom_from_base;
    std::vector<Eigen::Vector2d> points;
    double travel = 0;   // [m] path (turns counted) from the first view
  };
  double spacing_, length_, turn_as_travel_;
  std::deque<View> views_;
};

}  // namespace rgnav::localizer
