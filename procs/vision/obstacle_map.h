// The vision's 3D occupancy around the robot and its column projection (diss. 5.5; Holz et al.
// 4.2): stereo points go into an OctoMap with free space by ray casting; the laser goes into a
// one-cell-high layer of its own at its height; seen floor and drop-offs into a floor layer.
// project() fuses the laser layer with the stereo cells of the same height (a weighted mean by
// each sensor's reliability, as in 5.5) and projects the height band [min_height, max_height]
// along the columns into an egocentric 2D grid.
//
// All three trees are in the odometry frame, shifted by an anchor so that OctoMap's 16-bit keys
// never run out on a long drive (the map is started afresh around the robot when it moves
// `reanchor_distance` from the anchor). Nodes farther than keep_radius from the robot are
// deleted whenever it moved trim_distance: the map's memory is bounded by the area around it.
#pragma once

#include <octomap/OcTree.h>

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"
#include "vision/view_forgetting.h"

namespace rgnav::vision {

struct ObstacleMapOptions
{
  double resolution = 0.05;        // [m] voxel edge (and grid cell edge)
  double max_range = 4.0;          // [m] stereo points farther than this: free space up to it, no obstacle
  double stereo_prob_hit = 0.7;    // OctoMap sensor model of the stereo points
  double stereo_prob_miss = 0.4;
  double laser_prob_hit = 0.8;     // ... and of the laser
  double laser_prob_miss = 0.35;
  double clamp_min = 0.12;         // OctoMap's clamping (cells stay this easy to change)
  double clamp_max = 0.97;
  // Fusion in the laser's layer: each sensor's occupancy is a mean with this standard
  // deviation; the fused cell is their inverse-variance weighted mean.
  double stereo_sigma = 0.3;
  double laser_sigma = 0.15;
  // Cells the laser sees occupied and stereo never saw: obstacles of the grid too, or only free
  // evidence. Collision avoidance reads the laser itself and takes the grid as static, so by
  // default the laser only corrects what stereo saw (a walking person would otherwise leave a
  // static trail in the grid).
  bool laser_only_obstacles = false;
  double laser_height = 0.40;      // [m] scan plane above the floor
  double laser_max_range = 6.0;    // [m] laser beams free space up to here
  double floor_tolerance = 0.06;   // [m] points within this of the floor are floor (Holz et al. 4.2) ...
  // ... plus the height error of one disparity_sigma of disparity error at the point's range
  // (far floor points move by decimetres along their ray), up to max_floor_tolerance.
  double disparity_sigma = 0.5;    // [px] at the matching scale
  double max_floor_tolerance = 0.2;  // [m]
  double drop_off_depth = 0.10;    // [m] points this far below the floor: a drop-off where their ray crosses it
  double min_height = 0.10;        // [m] height band projected into the grid (floor removal) ...
  double max_height = 1.45;        // [m] ... up to the robot's top plus a margin
  double max_point_height = 2.2;   // [m] points above (ceilings) are not inserted
  // Forgetting by evidence (view_forgetting.h), never by age alone: stereo cells that have been
  // in the camera's view this long (frame time) without a point on them go back to unknown
  // (0: never; cells a ray passes through are cleared anyway) ...
  double forget_in_view_after = 0.0;   // [s]
  // ... and stereo cells over a laser cell the laser saw occupied and now sees free: what stood
  // in the scan plane (a person) has gone, and what stereo saw of it above goes with it (that
  // column and its neighbours). Things the laser never sees in their column (table tops, chair
  // seats away from their legs) are not touched.
  bool laser_clears_stereo = true;
  double keep_radius = 5.0;        // [m] horizontal reach of the map around the robot
  double trim_distance = 0.5;      // [m] travel between deletions beyond keep_radius
  double reanchor_distance = 400.0;  // [m] travel from the anchor that starts the map afresh
  double grid_size = 8.0;          // [m] edge of the square egocentric grid
};

// Egocentric grid of the occupancy in the height band (obstacle_grid_t's fields as plain data).
struct ObstacleGrid
{
  int64_t utime = 0;
  geometry::Pose2 odom_from_grid;   // corner of cell (0, 0), axes of the odometry frame
  double resolution = 0;
  int width = 0, height = 0;
  std::vector<int8_t> cells;        // row-major from min y: -1 unknown, 0 free ... 100 occupied
  double min_height = 0, max_height = 0;

  int8_t at(int x, int y) const { return cells[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; }
  // Cell of an odometry-frame point, or false when outside.
  bool cell_of(const Eigen::Vector2d& odom_point, int* x, int* y) const;
};

struct InsertStats
{
  size_t points = 0;      // points given to OctoMap (floor, obstacles and far free rays)
  size_t drop_offs = 0;   // points below the floor
  double seconds = 0;     // spent in OctoMap's insertion
};

class ObstacleMap
{
 public:
  explicit ObstacleMap(const ObstacleMapOptions& options);

  const ObstacleMapOptions& options() const { return options_; }

  // Stereo points in the base frame at capture, the camera's position in it, and where the
  // robot was (odometry frame). focal_baseline: f * B [px m] of the matching camera, for the
  // depth error of a point (0: exact points). Floor points are put on the floor plane along
  // their ray. Moves the map's bounds with the robot. utime: capture time; view: what the
  // camera could see (both needed for forget_in_view_after; without them nothing is forgotten
  // but what rays pass through).
  InsertStats insert_stereo(const std::vector<Eigen::Vector3f>& base_points, const Eigen::Vector3d& base_camera,
                            const geometry::Pose2& odom_from_base, double focal_baseline = 0.0, int64_t utime = 0,
                            const StereoView* view = nullptr);
  // A laser scan taken at odom_from_base, base_from_laser its mounting.
  void insert_laser(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base,
                    const geometry::Pose2& base_from_laser);
  // Forgets everything (the odometry frame the map lives in was restarted).
  void reset();
  // The egocentric grid around the robot at odom_from_base.
  ObstacleGrid project(const geometry::Pose2& odom_from_base, int64_t utime) const;

  size_t leaf_count() const;
  size_t memory_bytes() const;
  int trims() const { return trims_; }
  int64_t forgotten() const { return forgotten_; }   // stereo cells forgotten after being in view unhit
  int64_t laser_cleared() const { return laser_cleared_; }   // stereo cells cleared over what the laser saw leave
  int reanchors() const { return reanchors_; }

 private:
  octomap::point3d to_tree(const Eigen::Vector3d& odom) const;
  void follow(const geometry::Pose2& odom_from_base);
  void trim(const Eigen::Vector2d& odom_center);
  void reset_trees();
  // Stereo cells of the columns at and around a laser cell back to unknown; returns how many.
  int64_t clear_stereo_column(const octomap::point3d& laser_cell);

  const ObstacleMapOptions options_;
  std::unique_ptr<octomap::OcTree> stereo_;   // 3D
  std::unique_ptr<octomap::OcTree> laser_;    // one layer at laser_height
  std::unique_ptr<octomap::OcTree> floor_;    // one layer at z = 0: > 0.5 drop-off, < 0.5 floor seen
  Eigen::Vector2d anchor_ = Eigen::Vector2d::Zero();   // odometry position of the trees' origin
  bool anchored_ = false;
  Eigen::Vector2d last_trim_ = Eigen::Vector2d::Zero();
  int trims_ = 0;
  int reanchors_ = 0;
  ViewForgetting forgetting_;
  int64_t forgotten_ = 0;
  int64_t laser_cleared_ = 0;
};

}  // namespace rgnav::vision
