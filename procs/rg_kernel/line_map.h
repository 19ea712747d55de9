// 2D line segment maps from laser scans (diss. 3.1.1, 5.2): every scan is cut into line
// segments (split-and-merge over the ordered scan points, total least squares fits), and the
// region's map merges them with the dissertation's restrictive laser parameters — segments
// whose angles differ by less than alpha_max, whose mean end-point distance to each other's
// line D_L is below D_L^max, and that overlap or leave a gap below D_gap^max become one
// segment spanning the two farthest end points. 30 scans of ~150 points compress to ~40
// segments (factor ~50, diss. Fig. 5.4).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "geometry/pose2.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

// [m] a line segment's length.
inline double length(const rgmap::LineSegment& s) { return (s.b - s.a).norm(); }

struct ExtractOptions
{
  double split_distance = 0.03;    // [m] a point farther than this from the fitted line splits it
  double noise_split_factor = 3.0; // ... or farther than this many range noise sigmas (estimate_range_noise)
  double max_point_gap = 0.25;     // [m] consecutive points farther apart belong to different segments
  int min_points = 5;              // fewer points make no segment
  double min_length = 0.15;        // [m]
};

struct MergeOptions
{
  double alpha_max = 3.0 * M_PI / 180.0;  // [rad]
  double dl_max = 0.020;                  // [m]
  double gap_max = 0.150;                 // [m]
  double noise_dl_factor = 3.0;           // D_L^max is at least this many range noise sigmas
};

// The range noise of a scan [m]: the robust spread (median absolute deviation) of each point's
// distance to the chord of its two neighbours, over neighbours closer than max_point_gap (for
// independent noise sigma that distance has sigma * sqrt(1.5)). The dissertation's restrictive
// parameters suit a SICK LMS at mm resolution (sigma ~5 mm); logs stored with coarser ranges
// (e.g. 5 cm steps: sigma ~1.5 cm) break straight walls into staircases and keep observations
// of one wall apart unless the tolerances follow the noise. 0 if the scan has too few triples.
double estimate_range_noise(const std::vector<Eigen::Vector2d>& points, double max_point_gap);

// points: scan end points in scan order (beam order), in any common frame. range_noise: the
// scan's noise sigma [m] (0: the configured split distance alone).
std::vector<rgmap::LineSegment> extract_segments(const std::vector<Eigen::Vector2d>& points, const ExtractOptions& o,
                                                 double range_noise = 0);

// Merges until no pair qualifies (which pairs merge first can matter where merges chain).
//
// Two segments merge (diss. 3.1.1) if their angles differ by less than alpha_max (for a segment
// too short for its direction to be known that well: by less than its end points can swing
// within D_L^max), if D_L — the mean distance of one's end points to the other's line, in the
// direction that gives the smaller value, i.e. measured against the better known line — is
// below D_L^max, and if they overlap along their common line or leave a gap below D_gap^max.
// The merged segment lies on the common line, fitted by total least squares to the points
// behind both (each segment weighted by its support), spanning the farthest projected end
// points: repeated observations of a wall average out instead of the map drifting with
// whichever end points lie farthest apart.
// range_noise: the sigma [m] of the scan the segments come from (raises D_L^max, see MergeOptions).
std::vector<rgmap::LineSegment> merge_segments(std::vector<rgmap::LineSegment> segments, const MergeOptions& o,
                                               double range_noise = 0);

// Merges freshly extracted segments into an already merged map: each new segment merges with the
// map segment that lies best on their common line (smallest D_L), and a segment that grew by
// merging is tried again (merges cascade). Costs O(new x map) instead of O(map^2), so a region's
// map is updated per scan at constant cost.
// pose_error: the rigid correction that would align the fresh segments' scan with the map
// (line_alignment.h), if known: a fresh segment may then lie as much farther from its map
// segment as the correction moves its end points — the pose error, not the geometry. Nothing
// is moved: the merged segment averages the observations (their common line).
std::vector<rgmap::LineSegment> merge_into(std::vector<rgmap::LineSegment> map, std::vector<rgmap::LineSegment> fresh,
                                           const MergeOptions& o, double range_noise = 0,
                                           const geometry::Pose2* pose_error = nullptr);

// Mean distance of the four end points to the other segment's line (D_L of diss. Fig. 3.3).
double line_distance(const rgmap::LineSegment& a, const rgmap::LineSegment& b);

}  // namespace rgnav::rg_kernel
