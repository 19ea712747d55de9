// Everything the RG kernel keeps about the scans of one region, and what it derives from
// them: the merged line map (incrementally), and at finalisation — or whenever the open
// region is published — the bounding rectangle and the freespace bitmap from in-region
// measurements only: a beam that crosses a gateway line (diss. 5.2) or a doorway of the line map
// the robot never went through ends there, though its line segments stay in the line map for
// localization.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <unordered_set>
#include <vector>

#include "geometry/pose2.h"
#include "persist/byte_codec.h"
#include "procs/rg_kernel/doorways.h"
#include "procs/rg_kernel/gateway_geometry.h"
#include "procs/rg_kernel/line_alignment.h"
#include "procs/rg_kernel/line_map.h"
#include "procs/rg_kernel/line_map_fidelity.h"
#include "procs/rg_kernel/object_grouping.h"
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
  LineAlignOptions align;              // scans aligned to the line map before merging (line map only)
  double freespace_resolution = 0.15;  // [m] (diss.: 15 cm)
  double freespace_max_range = 8.0;    // [m] beams are carved up to this length
  double robot_radius = 0.26;          // [m] the cells under the robot at each scan are free (robot.yaml radius_m)
  // [m] the exact freespace leaves out what the robot only saw through a passage narrower than
  // this (freespace_trim.h); 0: off
  double freespace_min_passage = 1.0;
  // Scan points in space the region has seen free all around them (the 5 x 5 freespace cells
  // about the point) are something that moved there — a person walking, a door swung — and no
  // part of the line map or its 2D objects (the map is of the static structure; collision
  // avoidance sees what moves). A wall's point always has unseen cells behind it.
  bool drop_points_in_free_space = true;
  ObjectOptions objects;               // 2D objects (rectangles, circles), diss. 3.1-3.2
  DoorwayOptions doorways;             // the exact freespace also ends at doorways of the line map never crossed
};

// The far side of one of the region's own gateway lines: the region beyond it. A scan taken
// there (its laser origin just beyond the line, less than `reach` from it and not beside its
// ends) is no in-region measurement (diss. 5.2): it keeps its line segments (localization uses
// them) but carves no freespace, or its beams would put the room beyond into this region. Such
// scans stay behind when the crossing is reported late, at a pose a loop closure moved later,
// or when the robot turns back in a doorway.
struct ForeignSide
{
  EdgeFrame edge;       // region frame; normal pointing into the region beyond
  double reach = 3.0;   // [m]
};

class RegionBuilder
{
 public:
  explicit RegionBuilder(RegionBuildOptions options) : options_(std::move(options)) {}

  // Adds a scan: its segments are merged into the line map and its beams carved into the
  // freespace at once. A newer revision of a stored scan (a loop-closure correction) marks
  // the region for a rebuild from all its scans, done once at the next read — merged
  // segments and carved cells cannot be un-merged, and corrections come in bursts.
  void add_scan(StoredScan scan);
  // Removes a scan (it turned out to belong to another region); the caches are rebuilt at the
  // next read, like after a correction. Unknown ids are ignored.
  void remove_scan(int64_t scan_id);
  const std::vector<rgmap::LineSegment>& segments() const;
  const std::map<int64_t, StoredScan>& scans() const { return scans_; }
  int64_t raw_points() const;
  // Every raw end point of the region's scans against its line map (line_map_fidelity.h).
  LineMapFidelity fidelity(double tolerance, double cap) const;

  using GatewayLines = std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>;
  // Fills bbox, freespace, accuracy/completeness, segments and 2D objects of `region`. Exact (at
  // finalisation): recomputed from all beams, each ending where it crosses one of the gateway
  // lines (points in the region frame) or a doorway of the line map the robot did not go through
  // (doorways.h). Otherwise (the open region, published often): from the cells carved as scans
  // arrived, which end only at the gateways known then.
  // Exact descriptions also leave out the freespace of scans taken on a `foreign` side.
  void describe(rgmap::Region* region, const GatewayLines& gateway_lines, bool exact,
                const std::vector<ForeignSide>& foreign = {}) const;
  // Gateways of the region known when later scans are carved (beams crossing them are skipped).
  void set_gateway_lines(GatewayLines lines) { gateway_lines_ = std::move(lines); }

  // The region's scan ids, oldest first (by time, then id).
  std::vector<int64_t> scan_ids_by_time() const;
  // Robot positions (laser origins) in the region frame, oldest first: those of scan_ids_by_time().
  std::vector<Eigen::Vector2d> laser_origins() const;

  // Snapshot of everything, caches included (so a restored builder merges the next scan into
  // exactly the same line map). `shared_points(id)`: the scan's points if the caller stores
  // them already (they are then written once, by the caller), else nullptr.
  using SharedPoints = std::function<const std::vector<Eigen::Vector2d>*(int64_t scan_id)>;
  void save(persist::ByteWriter& w, const SharedPoints& shared_points) const;
  // Into a freshly constructed builder; throws persist::CorruptBytes on malformed bytes.
  void load(persist::ByteReader& r, const SharedPoints& shared_points);

 private:
  void add_incrementally(const StoredScan& scan) const;
  // The two halves of add_incrementally: the scan's lines and circles merged into the caches
  // (from its points not in free space seen so far), and its free wedges carved.
  void add_lines(const StoredScan& scan) const;
  void carve(const StoredScan& scan) const;
  // True if the 5 x 5 freespace cells about p (region frame) are all free.
  bool in_free_space(const Eigen::Vector2d& p) const;
  void refresh() const;
  void fill_objects(rgmap::Region* region) const;
  void fill_region(rgmap::Region* region, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                   const std::vector<std::pair<int32_t, int32_t>>& cells) const;

  const RegionBuildOptions options_;
  std::map<int64_t, StoredScan> scans_;   // by scan id: deterministic order
  GatewayLines gateway_lines_;
  // Caches derived from scans_, rebuilt lazily after corrections.
  mutable bool stale_ = false;
  mutable std::vector<rgmap::LineSegment> segments_;
  mutable std::unordered_set<uint64_t> free_cells_;   // cell (x, y) of the region frame grid
  mutable std::map<int64_t, std::vector<CircleObservation>> circle_observations_;   // by scan id
  mutable Eigen::Vector2d lo_{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  mutable Eigen::Vector2d hi_{-std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
};

}  // namespace rgnav::rg_kernel
