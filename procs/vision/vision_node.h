// Node adapter of the vision: STEREO_IMAGES, ODOMETRY and LASER_FRONT in, OBSTACLES_3D out
// (one grid per processed frame). A frame is processed once odometry brackets its capture time
// (within max_pose_gap); only the newest frame waits, so a slow frame never queues the next
// ones (a newer frame replaces the waiting one). Frames that name another calibration, do not
// decode, or do not have the calibration's size are dropped and counted, as are malformed
// messages. Laser scans are fused at most every laser_period. Odometry that goes back in time
// or sequence (a restarted base driver or log) starts the map afresh in the new frame.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "geometry/pose2.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/stereo_images_t.hpp"
#include "runtime/node.h"
#include "sensors/laser_scan.h"
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

  int64_t frames_processed() const { return frames_; }
  int64_t frames_superseded() const { return superseded_; }
  int64_t laser_scans_fused() const { return lasers_; }
  int64_t map_resets() const { return resets_; }
  const VisionPipeline& pipeline() const { return pipeline_; }
  const FrameResult& last_result() const { return last_; }

 private:
  struct OdometrySample
  {
    int64_t utime;
    geometry::Pose2 odom_from_base;
  };

  void on_stereo(const stereo_images_t& m);
  void on_odometry(const odometry_t& m);
  void on_laser(const laser_scan_t& m);
  std::optional<geometry::Pose2> odometry_at(int64_t utime) const;
  // Newest odometry is so far past `utime` that the samples around it are all there is.
  bool odometry_past(int64_t utime) const;
  void try_frame();
  void try_laser();
  void drop_frame(const std::string& why);
  void report();

  runtime::Node& node_;
  const VisionNodeOptions options_;
  VisionPipeline pipeline_;
  const int64_t max_gap_us_;
  const int64_t laser_period_us_;
  std::deque<OdometrySample> odometry_;
  int64_t last_odometry_seq_ = -1;
  std::optional<StereoFrame> pending_frame_;
  std::optional<sensors::LaserScan> pending_laser_;
  int64_t last_frame_utime_ = 0;
  int64_t last_laser_utime_ = 0;     // newest fused scan
  int64_t last_scan_id_ = 0;         // newest laser scan's id (OBJECTS_3D re-anchoring)
  int64_t frames_ = 0, superseded_ = 0, lasers_ = 0, resets_ = 0;
  FrameResult last_;
  std::chrono::steady_clock::time_point last_frame_wall_{};
  std::string reported_;
};

}  // namespace rgnav::vision
