// Node adapter of the vision: STEREO_IMAGES, ODOMETRY and LASER_FRONT in, OBSTACLES_3D out
// (one grid per processed frame). The order of frames, odometry and scans is FrameSync's
// (frame_sync.h: a frame waits for the odometry around it, only the newest one waits, scans at
// most every laser_period, odometry going back starts the map afresh). Frames that name another
// calibration, do not decode, or do not have the calibration's size are dropped and counted, as
// are malformed messages.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "geometry/pose2.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/stereo_images_t.hpp"
#include "runtime/node.h"
#include "vision/frame_sync.h"
#include "vision/vision_options.h"
#include "vision/vision_pipeline.h"

namespace rgnav::vision {

class VisionNode
{
 public:
  // Throws config::ConfigError when the rig is unusable (names the calibration file).
  VisionNode(runtime::Node& node, const VisionNodeOptions& options, const StereoRig& rig);
  VisionNode(const VisionNode&) = delete;
  VisionNode& operator=(const VisionNode&) = delete;

  int64_t frames_processed() const { return sync_.frames_processed(); }
  int64_t frames_superseded() const { return sync_.frames_superseded(); }
  int64_t laser_scans_fused() const { return sync_.laser_scans_fused(); }
  int64_t map_resets() const { return sync_.map_resets(); }
  const VisionPipeline& pipeline() const { return pipeline_; }
  const FrameResult& last_result() const { return last_; }

 private:
  void on_stereo(const stereo_images_t& m);
  void on_odometry(const odometry_t& m);
  void on_laser(const laser_scan_t& m);
  void on_processed(const StereoFrame& f, const FrameResult& r);
  void drop_frame(const std::string& why);
  void report();

  runtime::Node& node_;
  const VisionNodeOptions options_;
  VisionPipeline pipeline_;
  FrameSync sync_;
  int64_t last_frame_utime_ = 0;
  int64_t last_scan_id_ = 0;         // newest laser scan's id (OBJECTS_3D re-anchoring)
  FrameResult last_;
  std::chrono::steady_clock::time_point last_frame_wall_{};
  std::string reported_;
};

}  // namespace rgnav::vision
