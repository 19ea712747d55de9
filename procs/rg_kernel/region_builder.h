// Everything the RG kernel keeps about the scans of one region, and what it derives from
// them: the merged line map (incrementally), and at finalisation — or whenever the open
// region is published — the bounding rectangle and the freespace bitmap from in-region
// measurements only: a beam that crosses one of the region's gateway lines is filtered out
// (diss. 5.2), though its line segments stay in the line map for localization.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <vector>

#include "geometry/pose2.h"
#include "procs/rg_kernel/line_map.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

struct StoredScan
{
  int64_t scan_id = 0;
  int64_t utime = 0;
  int32_t revision = 0;
  geometry::Pose2 region_from_laser;          // laser pose in the region frame
  std::vector<Eigen::Vector2d> laser_points;  // valid end points, laser frame, beam order
};

struct RegionBuildOptions
{
  ExtractOptions extract;
  MergeOptions merge;
  double freespace_resolution = 0.15;  // [m] (diss.: 15 cm)
  double freespace_max_range = 8.0;    // [m] beams are carved up to this length
};

class RegionBuilder
{
 public:
  explicit RegionBuilder(RegionBuildOptions options) : options_(std::move(options)) {}

  // Adds a scan (or replaces an earlier revision of the same scan id; then the line map is
  // rebuilt from all stored scans, since merged segments cannot be un-merged).
  void add_scan(StoredScan scan);
  const std::vector<rgmap::LineSegment>& segments() const { return segments_; }
  const std::map<int64_t, StoredScan>& scans() const { return scans_; }
  int64_t raw_points() const;

  // Fills bbox, freespace, features-related fields and segments of `region`; gateway lines
  // are pairs of points in the region frame that beams must not cross.
  void describe(rgmap::Region* region, const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& gateway_lines) const;

  // Robot positions (laser origins) in the region frame, oldest first.
  std::vector<Eigen::Vector2d> laser_origins() const;

 private:
  void rebuild_lines();

  const RegionBuildOptions options_;
  std::map<int64_t, StoredScan> scans_;   // by scan id: deterministic order
  std::vector<rgmap::LineSegment> segments_;
};

// True if segment p-q properly crosses segment a-b.
bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

}  // namespace rgnav::rg_kernel
