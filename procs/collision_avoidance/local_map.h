// The local obstacle map collision avoidance reasons on: obstacle points in the odometry
// frame from the last few laser scans (each placed with the odometry pose at its time) and
// the occupied cells of the newest OBSTACLES_3D grid, in a uniform hash grid for fast
// "how far is the nearest obstacle from here?" queries. Points older than `max_age` or
// farther than `max_range` from the robot are dropped from the recent set; the 3D grid, a map
// that may arrive seconds after its frame, holds until replaced (at most `memory`).
//
// A short-term memory keeps what the 180 degree laser no longer sees: one point per
// memory cell, for up to `memory` seconds, until a newer scan looks through its place (its
// beams there reach farther: the obstacle moved away). Without it a box the robot is
// passing beside, or one it turned away from, vanished after max_age, the planner drove
// into it, saw it again and turned away: over the obstacle courses the robot oscillated in
// front of gaps it could pass (28 % of the courses reached). A distance field over the points
// (OpenCV's distance transform, rebuilt with the index) answers the common query "is
// anything within r?" in constant time where the answer is clearly no; only near obstacles
// does the exact search over the points run. The planner asks thousands of these per
// decision, and the process must keep its heartbeat on a loaded machine.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include <deque>
#include <unordered_map>
#include <vector>

#include "collision_avoidance/people_tracker.h"
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
  // Static or moving: a cell (of `cell`) hit without a gap longer than occupancy_gap for at
  // least static_after is static (walls, door frames, furniture, people standing); younger
  // hits are possibly moving (people walking, or stepping out from behind something), and
  // the planner keeps more distance to them.
  double static_after = 1.0;  // [s]
  double occupancy_gap = 0.3; // [s]
  // Short-term memory of what is out of view (0 disables it).
  double memory = 10.0;        // [s]
  double memory_cell = 0.05;   // [m] one remembered point per cell
  double clear_margin = 0.10;  // [m] a newer beam must pass this far beyond a point to clear it
  double view_interval = 0.25; // [s] one field-of-view outline kept per interval (for detours)
  // Movers tracked over the possibly moving points; their predicted paths are obstacles.
  PeopleTrackerOptions people;
};

// A scan's obstacle readings in the robot's base frame.
struct ScanPoints;

// One scan's beams as (bearing, free range) around the laser, in bearing order: what the scan
// says about a place in the odom frame (people_tracker.h SeenNow).
class BeamView
{
 public:
  BeamView(const ScanPoints& scan, double margin);
  // Both beams around the point reach past it by `margin`: free now; both end short of it
  // by `margin`: hidden; otherwise (one of them ends at it) still there. One beam only
  // would free the corners of a box a neighbouring beam grazes.
  SeenNow look(const Eigen::Vector2d& odom_point) const;
  // Something at the point stands apart from what is behind it: the beams ending within
  // `radius` of it are flanked by beams that end no nearer than the nearest of them, one at
  // least `jump` farther. A person standing in a room or a hallway does; a piece of wall,
  // seen head-on or at a grazing angle (its near side ends nearer), does not.
  bool stands_apart(const Eigen::Vector2d& odom_point, double radius, double jump) const;
  bool empty() const { return beams_.size() < 2; }

 private:
  std::vector<std::pair<double, double>> beams_;
  Pose2 laser_from_odom_;
  double margin_;
};

struct ScanPoints
{
  time::Time stamp{};
  Pose2 odom_from_base;                 // pose at the scan's time
  std::vector<Eigen::Vector2d> points;  // base frame
  // What the scan saw as free: the polygon from the laser position through every beam's end
  // (a hit, or the range limit for no return), base frame; empty if not known.
  Eigen::Vector2d laser_origin = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> outline;
};

class LocalMap
{
 public:
  explicit LocalMap(const LocalMapOptions& options) : options_(options), tracker_(options.people) {}

  void add_scan(ScanPoints scan);
  // Replaces the 3D-derived obstacles (points in the odom frame).
  void set_grid_points(time::Time stamp, std::vector<Eigen::Vector2d> odom_points);
  // Drops what is too old at `now` and rebuilds the index.
  void rebuild(time::Time now);

  // Distance from p (odom frame) to the nearest obstacle point, searching up to `radius`
  // (infinity if none).
  double clearance(const Eigen::Vector2d& p, double radius) const;
  // The same, leaving out where tracked movers are only predicted to be: what is there now.
  double clearance_observed(const Eigen::Vector2d& p, double radius) const;
  size_t size() const { return points_.size(); }
  const std::vector<Eigen::Vector2d>& points() const { return points_; }
  // points()[i] is only where a tracked mover is predicted to be (not seen there).
  bool predicted_only(size_t i) const { return i >= predicted_begin_ && i < predicted_end_; }
  // Distance from p to the nearest possibly moving point within `radius` (infinity if none).
  double clearance_moving(const Eigen::Vector2d& p, double radius) const;
  size_t moving_size() const { return moving_.size(); }
  // The scans kept (after the last rebuild's pruning), oldest first.
  const std::deque<ScanPoints>& scans() const { return scans_; }
  // What the laser saw over the memory time: one outline per view_interval (no points),
  // oldest first, ending with the newest scan's.
  const std::deque<ScanPoints>& views() const { return views_; }
  size_t remembered_size() const { return remembered_.size(); }
  // Distance from p to the nearest predicted position of a tracked mover within `radius`
  // (infinity if none): standing there means standing in someone's way.
  double clearance_predicted(const Eigen::Vector2d& p, double radius) const;
  const PeopleTracker& tracker() const { return tracker_; }
  // What the newest scan says about p (odom frame): unknown without scans.
  SeenNow seen_now(const Eigen::Vector2d& p) const;
  // BeamView::stands_apart on the newest scan (false without scans).
  bool stands_apart(const Eigen::Vector2d& p, double radius, double jump) const;
  double max_range() const { return options_.max_range; }

 private:
  void build_field();
  double nearest(const Eigen::Vector2d& p, double radius, bool observed_only) const;
  void forget_seen_through(const BeamView& view);
  int64_t memory_key(const Eigen::Vector2d& p) const
  {
    return key(static_cast<int>(std::floor(p.x() / options_.memory_cell)),
               static_cast<int>(std::floor(p.y() / options_.memory_cell)));
  }
  int64_t cell_key(const Eigen::Vector2d& p) const
  {
    return key(static_cast<int>(std::floor(p.x() / options_.cell)), static_cast<int>(std::floor(p.y() / options_.cell)));
  }
  int64_t key(int ix, int iy) const { return (static_cast<int64_t>(ix) << 32) ^ static_cast<uint32_t>(iy); }

  const LocalMapOptions options_;
  std::deque<ScanPoints> scans_;
  std::deque<ScanPoints> views_;
  struct Remembered
  {
    Eigen::Vector2d point;  // odom frame, the newest hit in the cell
    time::Time stamp{};
  };
  std::unordered_map<int64_t, Remembered> remembered_;  // memory cells
  time::Time grid_stamp_{};
  std::vector<Eigen::Vector2d> grid_points_;
  std::vector<Eigen::Vector2d> points_;  // odom frame, all sources
  std::unordered_map<int64_t, std::vector<uint32_t>> index_;
  struct CellHits
  {
    time::Time first{};  // start of the current unbroken run of hits
    time::Time last{};
  };
  std::unordered_map<int64_t, CellHits> hits_;  // odom-frame cells of `cell`
  std::vector<Eigen::Vector2d> moving_;         // points in young cells, and the predicted ones
  PeopleTracker tracker_;
  std::vector<Eigen::Vector2d> predicted_;      // where tracked movers will be (odom frame)
  size_t predicted_begin_ = 0, predicted_end_ = 0;  // ... and where they are in points_
  // Distance field: distance from each field cell's centre to the nearest point [m], over
  // field_origin_ + [0, cols) x [0, rows) cells of field_cell_.
  cv::Mat field_;
  Eigen::Vector2d field_origin_ = Eigen::Vector2d::Zero();
  static constexpr double field_cell_ = 0.05;
  static constexpr double kFieldPad = 2.5;  // [m] field margin beyond the points (queries up to this radius)
};

}  // namespace rgnav::collision_avoidance
