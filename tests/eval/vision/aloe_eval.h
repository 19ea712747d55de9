// Disparity of the vision's matcher on the Middlebury 2006 Aloe pair against its ground truth.
// Ground truth convention (OpenCV ximgproc's readGT for Middlebury PNGs, the source of this
// copy): 8-bit grey = disparity in pixels at the images' resolution, 0 = unknown. A pixel with
// ground truth is bad when the estimate is missing or differs by more than the threshold.
#pragma once

#include <string>

#include "vision/dense_stereo.h"

namespace rgnav::vision::eval {

struct AloeResult
{
  int width = 0, height = 0;
  long gt_pixels = 0;            // pixels with ground truth
  double bad_ratio = 0;          // at threshold_px, missing estimates counted bad
  double bad_ratio_2px = 0;      // the same at 2 px
  double bad_ratio_estimated = 0;   // at threshold_px among pixels with an estimate
  double density = 0;            // share of ground-truth pixels with an estimate
  double scale_check = 0;        // median estimate / ground truth (1: the scale convention holds)
  double threshold_px = 1.0;
  double ms = 0;                 // matching time
  int gt_max = 0;
};

// Throws std::runtime_error when the images cannot be read.
AloeResult evaluate_aloe(const std::string& dir, const DisparityOptions& options, double threshold_px);

}  // namespace rgnav::vision::eval
