// The vision in a lock-step drive (tests/eval/control course_drive.h): after every simulator step
// the simulated head renders the world at the robot's true pose when a frame is due (the
// stereo_capture rate), encodes the pair as stereo_capture sends it, and the vision library
// takes frames, odometry and scans in the order the process does (vision/frame_sync.h); each
// processed frame's OBSTACLES_3D grid reaches collision avoidance `latency` after its capture,
// through the node's own conversion (collision_avoidance/grid_obstacles.h).
// For each contact it also says what the grid had shown of the solid that was hit (why the
// vision did not keep the robot off it: never marked, marked but forgotten, or marked too late).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "collision_avoidance/collision_avoidance.h"
#include "drivers/stereo/image_encoding.h"
#include "drivers/stereo/stereo_calibration.h"
#include "sim/simulator.h"
#include "sim/stereo_renderer.h"
#include "vision/frame_sync.h"
#include "vision/vision_options.h"
#include "vision/vision_pipeline.h"

namespace rgnav::bench {

struct HeadLoopOptions
{
  double rate_hz = 10.0;        // stereo_capture's capture.rate_hz
  double pan = 0.0, tilt = 0.0; // [rad] stereo_capture's fixed head angles
  stereo::Encoding encoding = stereo::Encoding::kJpeg;
  int jpeg_quality = 90;
  sim::StereoRenderOptions render;
  double latency_s = 0.15;      // [s] capture -> grid at collision avoidance (matching, transport)
  int grid_occupied_min = 50;   // collision avoidance's local_map.grid_occupied_min
};

// What the grids delivered to collision avoidance showed of the solid a contact was with.
struct ContactView
{
  std::string with;          // the simulator's name of the solid ("chair0.seat")
  double t_s = 0;            // [s] simulated time of the contact
  double grid_age_s = -1;    // [s] since the capture of the newest grid delivered (-1: none yet)
  int cells_now = 0;         // occupied cells of that grid on the solid's footprint
  int grids_marking = 0;     // delivered grids so far with at least one occupied cell on it
  double last_marked_age_s = -1; // [s] since the capture of the newest of those (-1: never)
};

class HeadInTheLoop
{
 public:
  HeadInTheLoop(const sim::World& world, const stereo::StereoCalibration& calibration,
                const vision::VisionNodeOptions& vision, const HeadLoopOptions& options);

  void after_step(const sim::Simulator& sim, const sim::StepOutput& out, collision_avoidance::CollisionAvoidance& ca);

  int64_t frames() const { return sync_->frames_processed(); }
  const std::vector<double>& frame_ms() const { return frame_ms_; }   // vision pipeline per frame (not the rendering)
  const std::vector<ContactView>& contacts() const { return contacts_; }

 private:
  struct Pending
  {
    int64_t due_utime;
    int64_t stamp;
    std::vector<Eigen::Vector2d> points;
  };
  struct Marked
  {
    int grids = 0;
    int cells_last = 0;       // on the newest delivered grid
    int64_t last_stamp = -1;
  };
  // Counts the grid's cells on each solid (odometry-frame points, odom_from_world now).
  void mark(const Pending& grid, const geometry::Pose2& world_from_odom);

  const HeadLoopOptions options_;
  const double resolution_;   // of the grid
  const sim::StereoRenderer renderer_;
  vision::VisionPipeline pipeline_;
  std::unique_ptr<vision::FrameSync> sync_;
  sim::StereoRender render_;
  std::deque<Pending> pending_;
  int64_t next_frame_utime_ = 0;
  uint64_t frame_no_ = 0;
  std::vector<double> frame_ms_;
  std::vector<sim::Box> solids_;   // boxes and table parts, world frame
  std::map<std::string, Marked> marked_;
  int64_t last_delivered_stamp_ = -1;
  geometry::Pose2 world_from_odom_;
  std::vector<ContactView> contacts_;
};

}  // namespace rgnav::bench
