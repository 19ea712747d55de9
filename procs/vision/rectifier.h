// Rectification of raw stereo pairs (cv::stereoRectify + initUndistortRectifyMap), with the
// maps computed once per rig: after it a scene point lies on the same row in both images and
// its depth is f * B / disparity.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vision/stereo_rig.h"

namespace rgnav::vision {

// The rectified left camera: a pinhole without distortion, the right camera `baseline` to its
// right on the x axis.
struct RectifiedCamera
{
  cv::Size size;
  double focal = 0;      // [px]
  double cx = 0, cy = 0; // [px] principal point (the same in both rectified images)
  double baseline = 0;   // [m]
  // Rectification turns the left camera: x_rectified = camera_from_rectified^T * x_camera.
  Eigen::Matrix3d camera_from_rectified = Eigen::Matrix3d::Identity();

  // The same camera on images scaled down by `factor` (1, 2, 4).
  RectifiedCamera scaled_down(int factor) const;
};

class Rectifier
{
 public:
  // alpha: cv::stereoRectify's free scaling (0 = only valid pixels, 1 = all source pixels).
  Rectifier(const StereoRig& rig, double alpha);

  const RectifiedCamera& camera() const { return camera_; }
  // True when the rig is already rectified (no distortion, parallel cameras): no remap needed.
  bool identity() const { return identity_; }
  // 8-bit grey or BGR images of the rig's size in, rectified 8-bit grey out.
  void rectify(const cv::Mat& left, const cv::Mat& right, cv::Mat* left_out, cv::Mat* right_out) const;

 private:
  RectifiedCamera camera_;
  bool identity_ = false;
  cv::Mat left_map1_, left_map2_, right_map1_, right_map2_;
};

}  // namespace rgnav::vision
