// Puts the vision's inputs in order before the pipeline sees them, as the process and every
// lock-step bench must do alike: a stereo frame is processed once odometry brackets its capture
// time (within max_pose_gap), and only the newest frame waits (a newer one replaces it, so a slow
// frame never queues the next ones); laser scans are fused at most every laser_period, also placed
// by the odometry around them; odometry that goes back in time or sequence (a restarted base
// driver or log) starts the map afresh in the new frame. No LCM: the node decodes and checks
// messages and hands them in here; results and drops come back through callbacks.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"
#include "vision/vision_pipeline.h"

namespace rgnav::vision {

struct FrameSyncOptions
{
  double max_pose_gap = 0.2;   // [s] odometry on both sides of a capture within this
  double laser_period = 0.1;   // [s] scans fused at most this often
  geometry::Pose2 base_from_laser{0.12, 0.0, 0.0};
};

struct FrameSyncCallbacks
{
  // A frame went through the pipeline (its odom_from_base set from the odometry).
  std::function<void(const StereoFrame&, const FrameResult&)> processed;
  // A frame or scan was dropped: why.
  std::function<void(const std::string&)> frame_dropped;
  std::function<void(const std::string&)> scan_dropped;
  // Called between the pipeline's stages (a process shows it is alive meanwhile).
  std::function<void()> between_stages;
};

class FrameSync
{
 public:
  // The pipeline is not owned and must outlive this.
  FrameSync(VisionPipeline& pipeline, const FrameSyncOptions& options, FrameSyncCallbacks callbacks);

  // Odometry in arrival order; returns true when it went back and the map was started afresh.
  bool on_odometry(int64_t utime, int64_t seq, const geometry::Pose2& odom_from_base);
  // A frame newer than any before (the caller checks that and the images); its pose is set here.
  void on_frame(StereoFrame frame);
  void on_laser(sensors::LaserScan scan);

  int64_t frames_processed() const { return frames_; }
  int64_t frames_superseded() const { return superseded_; }
  int64_t laser_scans_fused() const { return lasers_; }
  int64_t map_resets() const { return resets_; }
  int64_t last_odometry_seq() const { return last_odometry_seq_; }
  // Seconds the newest odometry is past `utime` (0 without odometry).
  double odometry_lead_s(int64_t utime) const;

 private:
  struct OdometrySample
  {
    int64_t utime;
    geometry::Pose2 odom_from_base;
  };

  std::optional<geometry::Pose2> odometry_at(int64_t utime) const;
  // Newest odometry is so far past `utime` that the samples around it are all there is.
  bool odometry_past(int64_t utime) const;
  void try_frame();
  void try_laser();

  VisionPipeline& pipeline_;
  const FrameSyncOptions options_;
  const FrameSyncCallbacks callbacks_;
  const int64_t max_gap_us_;
  const int64_t laser_period_us_;
  std::deque<OdometrySample> odometry_;
  int64_t last_odometry_seq_ = -1;
  std::optional<StereoFrame> pending_frame_;
  std::optional<sensors::LaserScan> pending_laser_;
  int64_t last_laser_utime_ = 0;   // newest fused scan
  int64_t frames_ = 0, superseded_ = 0, lasers_ = 0, resets_ = 0;
};

}  // namespace rgnav::vision
