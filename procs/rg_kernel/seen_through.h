// Scan points on things that moved (people walking, a door swung), found by seeing through them:
// another scan of the region had beams on both sides of the point's bearing that reached well past
// it, so at that time nothing stood there (Hähnel et al., IROS 2003; the scan mapper leaves such
// points out of its matching the same way, scan_mapper/moving_points.h). The region's line map is
// of the static structure: its localizer and planner would take a person's legs for a wall.
//
// Unlike "the space about the point was seen free" (RegionBuildOptions::drop_points_in_free_space,
// 5 x 5 freespace cells), the test needs no free cells on every side: people walk half a metre
// from hallway walls, where the wall's own cells are never free. A wall is never seen through:
// the beams about a wall point hit the wall. A thin static thing (a table leg) is seen through only
// by beams that straddle it, which two neighbouring beams do only where they are farther apart than
// the leg is wide (a 5 cm leg at 0.5 degree spacing: beyond 5.7 m).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "geometry/pose2.h"

namespace rgnav::rg_kernel {

// One scan's beams (valid end points in beam order, laser frame) placed in the region.
class BeamView
{
 public:
  // Beams are evidence of free space up to max_reach (the freespace's max range: what the region
  // carves free it trusts that far).
  BeamView(const geometry::Pose2& region_from_laser, const std::vector<Eigen::Vector2d>& laser_points, double max_reach);
  // The two valid neighbouring beams about p's bearing (region frame; neighbours: no beam without
  // return between them) both reach past p by `margin`, and p's surface (normal, region frame;
  // zero: unknown) is not seen at a flatter incidence than acos(min_cos_incidence): there a small
  // pose error moves a beam's end along the surface by a lot (a wall seen grazing).
  bool sees_through(const Eigen::Vector2d& p, const Eigen::Vector2d& normal, double margin, double min_cos_incidence) const;
  const Eigen::Vector2d& origin() const { return origin_; }
  double reach() const { return max_range_; }

 private:
  Eigen::Matrix2d laser_from_region_;   // the rotation
  Eigen::Vector2d origin_;
  // Per valid beam, in beam order: its direction as a pseudo-angle (rising with the bearing, no
  // trigonometry: this test runs for every point of a region against every scan of it), its
  // range, and its beam number (neighbours: numbers one apart).
  std::vector<double> pseudo_angle_;
  std::vector<double> range_;
  std::vector<int32_t> beam_;
  double max_range_ = 0;          // [m] of the farthest return, at most max_reach
};

// Unit normals of a scan's points (any frame, beam order) from their neighbours closer than
// max_gap; zero where a point has none.
std::vector<Eigen::Vector2d> point_normals(const std::vector<Eigen::Vector2d>& points, double max_gap);

}  // namespace rgnav::rg_kernel
