// Synthetic rectified stereo pairs for the vision tests and bench: a random texture seen by
// an ideal rig, the right image the left shifted by the disparity f * B / Z.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

namespace rgnav::vision::synthetic {

struct Pair
{
  cv::Mat left, right;
};

// A fronto-parallel textured plane filling the view at disparity d (px).
inline Pair plane_pair(cv::Size size, int d, uint64_t seed)
{
  cv::RNG rng(seed);
  cv::Mat tex(size.height, size.width + d, CV_8UC1);
  rng.fill(tex, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(tex, tex, cv::Size(3, 3), 0.8);
  // right(u) = left(u + d): the point seen at u in the left image is at u - d in the right.
  return {tex.colRange(0, size.width).clone(), tex.colRange(d, size.width + d).clone()};
}

}  // namespace rgnav::vision::synthetic
