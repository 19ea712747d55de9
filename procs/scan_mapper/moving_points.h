// Points on things that moved (people walking, a door swinging), found by seeing through them:
// another scan's beams passed the place where the point is. Registration leaves them out.
//
// Why: a person walking along a hallway leaves a trail of leg points in the local map, and their
// surfaces face the laser, i.e. along the hallway's axis, the one direction the walls leave
// unconstrained. ICP then follows the person (a 0.6 m slip in the demo's hall_c). The test is the
// classic free-space one (e.g. Hähnel et al., IROS 2003): a point one scan saw is dynamic if a
// later (or earlier) scan's beams reach past it.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "scan_mapper/scan_types.h"

namespace rgnav::scan_mapper {

struct MovingPointOptions
{
  // A beam must pass the point by this much: covers the pose guess's error (the odometry's, a few
  // cm per step) and range noise. 0: the filter is off.
  double margin_m = 0.3;
  // Surfaces seen by the other scan at a flatter angle than this are not tested: there a small
  // pose error moves the beam's end along the surface by a lot (a wall seen grazing).
  double max_incidence_deg = 70.0;
};

// One scan's beams around its laser, placed in the map. Keeps a reference to the scan, which
// must outlive the view.
class ScanView
{
 public:
  ScanView(const sensors::LaserScan& scan, const Pose2& map_from_laser, const MovingPointOptions& options);
  // Both beams around p (map frame) reach past it by margin_m (a beam without return reaches to
  // the range limit). normal (map frame, or zero if unknown) is p's surface normal.
  bool sees_through(const Eigen::Vector2d& p, const Eigen::Vector2d& normal) const;

 private:
  const sensors::LaserScan& scan_;
  Pose2 laser_from_map_;
  Eigen::Vector2d origin_;
  double margin_;
  double min_cos_incidence_;
};

// keep[i] is cleared for every points[i] (map frame, normals[i] its normal when has_normal[i])
// that one of the views sees through.
void mark_seen_through(const std::vector<ScanView>& views, const Points& points, const Points& normals,
                       const std::vector<char>& has_normal, std::vector<char>* keep);

}  // namespace rgnav::scan_mapper
