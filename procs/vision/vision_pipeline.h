// One stereo frame through the vision: rectify, dense disparity, 3D points into the base
// frame through the head pose at capture, into the obstacle map, and the column projection.
// Plain types in and out; the node feeds it decoded images and odometry.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <functional>

#include "geometry/pose2.h"
#include "sensors/laser_scan.h"
#include "vision/dense_stereo.h"
#include "vision/object_rectangles.h"
#include "vision/obstacle_map.h"
#include "vision/rectangle_detector.h"
#include "vision/rectifier.h"
#include "vision/stereo_rig.h"

namespace rgnav::vision {

// 3D rectangles (diss. 3.3: doors, whiteboards, table tops) from the rectified left image and
// the frame's disparity (rectangle_detector.h), every few frames: line detection and grouping
// cost about as much as the matching.
struct RectangleOptions
{
  bool enabled = true;
  int every_frames = 3;
  RectangleDetectorOptions detector;  // its refine.focal_baseline is the rig's (set by the pipeline)
  KindOptions kinds;
};

struct VisionOptions
{
  double rectify_alpha = 0.0;   // cv::stereoRectify's free scaling: 0 keeps only valid pixels
  DisparityOptions disparity;
  PointOptions points;
  ObstacleMapOptions map;
  RectangleOptions rectangles;
};

struct StereoFrame
{
  int64_t utime = 0;
  cv::Mat left, right;              // 8-bit grey or BGR, the rig's size
  double pan = 0, tilt = 0;         // [rad] head at capture
  geometry::Pose2 odom_from_base;   // robot at capture
};

struct FrameResult
{
  ObstacleGrid grid;
  size_t points = 0;                // 3D points from the disparity
  InsertStats insert;
  bool rectangles_run = false;                 // this frame was one for rectangles
  std::vector<ObjectRectangle> rectangles;     // base frame at capture
  double rectify_ms = 0, disparity_ms = 0, points_ms = 0, map_ms = 0, project_ms = 0, rectangles_ms = 0, total_ms = 0;
};

class VisionPipeline
{
 public:
  // The rig must pass check_rig().
  VisionPipeline(const StereoRig& rig, const VisionOptions& options);

  // `between_stages` (if set) is called after each stage (matching, insertion, rectangles: up to
  // hundreds of ms each on a loaded core), so that a process can show it is alive meanwhile.
  FrameResult process(const StereoFrame& frame, const std::function<void()>& between_stages = {});
  void insert_laser(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base,
                    const geometry::Pose2& base_from_laser)
  {
    map_.insert_laser(scan, odom_from_base, base_from_laser);
  }

  void reset_map() { map_.reset(); }

  const StereoRig& rig() const { return rig_; }
  const RectifiedCamera& camera() const { return rectifier_.camera(); }
  bool rectifier_identity() const { return rectifier_.identity(); }
  const ObstacleMap& map() const { return map_; }

 private:
  const StereoRig rig_;
  const VisionOptions options_;
  Rectifier rectifier_;
  DenseStereo stereo_;
  RectifiedCamera matching_camera_;   // the rectified camera at the matching scale
  ObstacleMap map_;
  int64_t frames_ = 0;
};

}  // namespace rgnav::vision
