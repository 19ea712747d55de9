// What the vision process gives collision avoidance (OBSTACLES_3D: solids above or below the
// laser's plane, a table's top, seen by the stereo head and kept in its OctoMap), taken from
// the world's ground truth for the exploration benchmark: the real vision in the loop renders
// and matches every frame and would make each run several times slower (./rgnav bench vision
// measures it, and collision avoidance with it, on its own courses). Without it the robot
// presses against table tops its laser does not see and stands there, which says nothing of
// an explorer. As the plan benchmark's perfect localizer stands in for the localizer.
//
// Every period, the samples (sample_m apart) of the footprint of each solid the laser misses
// (it does not cross the laser's plane) and that reaches into the height band: a sample counts
// as seen once its top lies in the head's field of view (a fixed head at head_height looking
// ahead) within range, with no wall between; seen samples are remembered (the OctoMap's map
// round the robot) and those within grid_half_m of the robot are given to collision avoidance,
// in the odometry frame, as the node converts the vision's grid.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "geometry/pose2.h"
#include "sim/world.h"

namespace rgnav::explore_eval {

struct VisionStandInOptions
{
  double period_s = 0.2;           // [s] OBSTACLES_3D's rate (the vision's >= 5 Hz)
  double head_height = 1.25;       // [m] the cameras' centre (config/robot.yaml head_height_m)
  double fov_h = 65.0 * M_PI / 180.0;   // [rad] across (the simulated rig: 640 px at f = 500 px)
  double fov_v = 51.3 * M_PI / 180.0;   // [rad] up and down (480 px)
  double range_m = 2.5;            // [m] config/vision.yaml projection.max_range_m
  double min_height = 0.10;        // [m] config/vision.yaml's height band ...
  double max_height = 1.45;        // [m]
  double laser_height = 0.40;      // [m] config/robot.yaml laser_front.mount_height_m
  double grid_half_m = 4.0;        // [m] half of config/vision.yaml grid_size_m
  double sample_m = 0.05;          // [m] the grid's cell
};

class VisionStandIn
{
 public:
  VisionStandIn(const sim::World& world, const VisionStandInOptions& options);

  // Due every period_s of simulated time: the points for collision avoidance (odometry frame),
  // from the robot's true pose (world frame) and its odometry pose at the same time.
  bool due(double t_s) const { return t_s >= next_s_; }
  std::vector<Eigen::Vector2d> update(double t_s, const geometry::Pose2& world_from_base,
                                      const geometry::Pose2& odom_from_base);

  size_t samples() const { return samples_.size(); }
  size_t seen() const;

 private:
  struct Sample
  {
    Eigen::Vector2d at;   // world frame
    double top = 0;       // [m] the solid's top over this sample (within the band)
    bool seen = false;
  };
  bool wall_between(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  VisionStandInOptions options_;
  std::vector<Sample> samples_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls_;   // those reaching above the laser
  double next_s_ = 0;
};

}  // namespace rgnav::explore_eval
