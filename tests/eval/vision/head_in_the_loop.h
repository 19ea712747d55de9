// The vision in a lock-step drive (tests/eval/control course_drive.h): after every simulator step
// the simulated head renders the world at the robot's true pose when a frame is due (the
// stereo_capture rate), encodes the pair as stereo_capture sends it, and the vision library
// takes frames, odometry and scans in the order the process does (vision/frame_sync.h); each
// processed frame's OBSTACLES_3D grid reaches collision avoidance `latency` after its capture,
// through the node's own conversion (collision_avoidance/grid_obstacles.h).
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
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

class HeadInTheLoop
{
 public:
  HeadInTheLoop(const sim::World& world, const stereo::StereoCalibration& calibration,
                const vision::VisionNodeOptions& vision, const HeadLoopOptions& options);

  void after_step(const sim::Simulator& sim, const sim::StepOutput& out, collision_avoidance::CollisionAvoidance& ca);

  int64_t frames() const { return sync_->frames_processed(); }
  const std::vector<double>& frame_ms() const { return frame_ms_; }   // vision pipeline per frame (not the rendering)

 private:
  struct Pending
  {
    int64_t due_utime;
    int64_t stamp;
    std::vector<Eigen::Vector2d> points;
  };

  const HeadLoopOptions options_;
  const sim::StereoRenderer renderer_;
  vision::VisionPipeline pipeline_;
  std::unique_ptr<vision::FrameSync> sync_;
  sim::StereoRender render_;
  std::deque<Pending> pending_;
  int64_t next_frame_utime_ = 0;
  uint64_t frame_no_ = 0;
  std::vector<double> frame_ms_;
};

}  // namespace rgnav::bench
