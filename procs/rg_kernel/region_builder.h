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
#include "procs/rg_kernel/seen_through.h"
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
  // [m] Scan points another scan of the region saw through — beams on both sides of the point
  // reaching this much past it (seen_through.h), earlier or later, up to freespace_max_range — are
  // something that moved and no part of the line map or its 2D objects either; so are those a
  // later scan of another region saw through (see_through_by). A point found so after it was merged makes
  // the line map stale: it is rebuilt from all the scans (as after a loop-closure correction) when
  // the region is described exactly, and while it is open each time it has grown by a quarter
  // (the rebuilds together cost a few builds of the whole region). The margin covers the pose
  // error between the two scans and the range noise, as the scan mapper's. 0: off.
  double seen_through_margin = 0.3;
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
  // Called once per scan while the whole region is worked through again (a rebuild of the line
  // map, an exact description): seconds for a large region on a loaded core, during which a
  // process shows that it is alive (RgKernel::set_progress).
  void set_progress(std::function<void()> progress) { progress_ = std::move(progress); }
  // Another region's scan (its laser pose in this region's frame, points in its laser frame): the
  // points of this region it sees through are left out of the line map too (seen_through_margin),
  // as a walker seen last before a gateway is seen through from beyond it. True if any was not
  // already (the line map is then stale: describe the region again).
  bool see_through_by(const geometry::Pose2& region_from_laser, const std::vector<Eigen::Vector2d>& laser_points);

  // The region's scan ids, oldest first (by time, then id).
  std::vector<int64_t> scan_ids_by_time() const;
  // Robot positions (laser origins) in the region frame, oldest first: those of scan_ids_by_time().
  std::vector<Eigen::Vector2d> laser_origins() const;

  // Snapshot of everything, caches included (so a restored builder merges the next scan into
  // exactly the same line map). `shared_points(id)`: the scan's points if the caller stores
  // them already (they are then written once, by the caller), else nullptr.
  using SharedPoints = std::function<const std::vector<Eigen::Vector2d>*(int64_t scan_id)>;
  void save(persist::ByteWriter& w, const SharedPoints& shared_points) const;
  // Into a freshly constructed builder; throws persist::CorruptBytes on malformed bytes. `format`:
  // the kernel snapshot's (kernel_snapshot.cpp).
  void load(persist::ByteReader& r, const SharedPoints& shared_points, uint32_t format);

 private:
  void add_incrementally(const StoredScan& scan) const;
  // The two halves of add_incrementally: the scan's lines and circles merged into the caches
  // (from its points not in free space seen so far), and its free wedges carved.
  void add_lines(const StoredScan& scan) const;
  void carve(const StoredScan& scan) const;
  // True if the 5 x 5 freespace cells about p (region frame) are all free.
  bool in_free_space(const Eigen::Vector2d& p) const;
  // The new scan's points that a stored scan sees through, and the stored scans' points the new
  // scan sees through (seen_through_); marks the line map stale_ when it may hold one of the latter.
  void see_through(const StoredScan& scan) const;
  // Every scan's seen_through_ afresh (after corrections: their poses changed).
  void see_through_all() const;
  // A stale line map (seen_through_margin) is rebuilt now if `exact` or the region grew enough.
  void rebuild_if_seen_through(bool exact) const;
  void refresh() const;
  void fill_objects(rgmap::Region* region) const;
  void note_progress() const
  {
    if (progress_) progress_();
  }
  void fill_region(rgmap::Region* region, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                   const std::vector<std::pair<int32_t, int32_t>>& cells) const;

  const RegionBuildOptions options_;
  std::function<void()> progress_;        // set_progress
  std::map<int64_t, StoredScan> scans_;   // by scan id: deterministic order
  GatewayLines gateway_lines_;
  // Caches derived from scans_, rebuilt lazily after corrections.
  mutable bool stale_ = false;
  mutable std::vector<rgmap::LineSegment> segments_;
  mutable std::unordered_set<uint64_t> free_cells_;   // cell (x, y) of the region frame grid
  mutable std::map<int64_t, std::vector<CircleObservation>> circle_observations_;   // by scan id
  // Per scan id, per laser point: another scan of the region saw through it (seen_through_margin).
  mutable std::map<int64_t, std::vector<char>> seen_through_;
  // ... by another region's scan (see_through_by); kept through rebuilds and corrections.
  std::map<int64_t, std::vector<char>> seen_elsewhere_;
  mutable bool seen_through_valid_ = true;   // false after corrections and removals, until refresh
  // Derived from scans_ (not saved): each scan's beams, points and their normals in the region.
  struct SeenScan
  {
    BeamView view;
    std::vector<Eigen::Vector2d> points, normals;
    double reach = 0;   // [m] farthest point from the laser
    Eigen::Vector2d lo{0, 0}, hi{0, 0};   // the points' bounding box
  };
  // Whether any of one scan's points lies within the reach of another's beams (by its box).
  static bool may_meet(const SeenScan& points, const SeenScan& beams);
  const SeenScan& seen_scan(const StoredScan& scan) const;
  mutable std::map<int64_t, SeenScan> seen_scans_;
  // The line map may hold points seen through since they were merged; scans at its last rebuild.
  mutable bool holds_seen_through_ = false;
  mutable uint64_t scans_at_rebuild_ = 0;
  mutable Eigen::Vector2d lo_{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  mutable Eigen::Vector2d hi_{-std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
};

}  // namespace rgnav::rg_kernel
