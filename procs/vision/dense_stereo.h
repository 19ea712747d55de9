// Dense disparity by semi-global matching (cv::StereoSGBM) on a rectified pair, and the 3D
// points it implies in the rectified left camera's frame (Z = f * B / d).
#pragma once

#include <Eigen/Core>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "vision/rectifier.h"

namespace rgnav::vision {

struct DisparityOptions
{
  int downscale = 1;            // match on images scaled down by 1, 2 or 4 (cost falls with its square)
  int min_disparity = 0;        // [px] at the matching scale
  int num_disparities = 64;     // [px] searched range, a multiple of 16
  int block_size = 5;           // [px] odd, matching window
  int p1 = 0;                   // smoothness penalties; 0 = OpenCV's usual 8 * block_size^2 ...
  int p2 = 0;                   // ... and 32 * block_size^2
  int disp12_max_diff = 1;      // [px] left-right check
  int pre_filter_cap = 63;
  int uniqueness_ratio = 10;    // [%]
  int speckle_window_size = 100;   // [px] small blobs of disparity are removed ...
  int speckle_range = 2;        // ... when their disparity varies by less than this
  std::string mode = "sgbm_3way";  // sgbm | hh | sgbm_3way | hh4
  bool pad_left = true;         // also match the left border SGBM leaves out (a fifth of a 320 px image at 64 px)
};

struct PointOptions
{
  int stride = 2;               // every stride-th pixel in both directions, at the matching scale
  double min_depth = 0.3;       // [m] nearer disparities are taken as mismatches
  double max_depth = 8.0;       // [m] farther ones are too coarse (one pixel of disparity is metres)
};

class DenseStereo
{
 public:
  explicit DenseStereo(const DisparityOptions& options);

  const DisparityOptions& options() const { return options_; }
  // Disparity of a rectified 8-bit grey pair, CV_16S in 1/16 px (cv::StereoMatcher's scale), at
  // the matching scale; invalid pixels are below min_disparity * 16.
  cv::Mat disparity(const cv::Mat& left, const cv::Mat& right) const;

 private:
  const DisparityOptions options_;
  cv::Ptr<cv::StereoSGBM> sgbm_;
};

// Points of valid disparities in the rectified camera frame (x right, y down, z forward) of
// `camera` (at the disparity's scale).
std::vector<Eigen::Vector3f> disparity_to_points(const cv::Mat& disparity16, const RectifiedCamera& camera,
                                                 const PointOptions& options);

}  // namespace rgnav::vision
