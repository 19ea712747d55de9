#include "aloe_eval.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

namespace rgnav::vision::eval {

AloeResult evaluate_aloe(const std::string& dir, const DisparityOptions& options, double threshold_px)
{
  const cv::Mat left = cv::imread(dir + "/aloeL.jpg", cv::IMREAD_GRAYSCALE);
  const cv::Mat right = cv::imread(dir + "/aloeR.jpg", cv::IMREAD_GRAYSCALE);
  const cv::Mat gt = cv::imread(dir + "/aloeGT.png", cv::IMREAD_UNCHANGED);
  if (left.empty() || right.empty() || gt.empty()) throw std::runtime_error(dir + ": aloeL.jpg, aloeR.jpg or aloeGT.png unreadable");
  if (gt.type() != CV_8UC1 || gt.size() != left.size()) throw std::runtime_error(dir + "/aloeGT.png: not 8-bit grey of the images' size");
  AloeResult r;
  r.width = left.cols;
  r.height = left.rows;
  r.threshold_px = threshold_px;
  const DenseStereo stereo(options);
  const auto t0 = std::chrono::steady_clock::now();
  const cv::Mat d16 = stereo.disparity(left, right);
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double scale = options.downscale;   // estimates at the matching scale -> full-size pixels
  long bad = 0, bad2 = 0, estimated = 0, bad_est = 0;
  std::vector<double> ratios;
  for (int v = 0; v < gt.rows; ++v)
    for (int u = 0; u < gt.cols; ++u) {
      const int g = gt.at<uint8_t>(v, u);
      if (g == 0) continue;
      r.gt_max = std::max(r.gt_max, g);
      ++r.gt_pixels;
      const int dv = std::min(v / options.downscale, d16.rows - 1), du = std::min(u / options.downscale, d16.cols - 1);
      const int16_t e16 = d16.at<int16_t>(dv, du);
      if (e16 < options.min_disparity * 16 || e16 <= 0) {
        ++bad;
        ++bad2;
        continue;
      }
      const double e = e16 / 16.0 * scale;
      ++estimated;
      if ((v % 8) == 0 && (u % 8) == 0) ratios.push_back(e / g);
      const double err = std::abs(e - g);
      if (err > threshold_px) {
        ++bad;
        ++bad_est;
      }
      if (err > 2.0) ++bad2;
    }
  if (r.gt_pixels > 0) {
    r.bad_ratio = static_cast<double>(bad) / r.gt_pixels;
    r.bad_ratio_2px = static_cast<double>(bad2) / r.gt_pixels;
    r.density = static_cast<double>(estimated) / r.gt_pixels;
  }
  if (estimated > 0) r.bad_ratio_estimated = static_cast<double>(bad_est) / estimated;
  if (!ratios.empty()) {
    std::nth_element(ratios.begin(), ratios.begin() + static_cast<long>(ratios.size() / 2), ratios.end());
    r.scale_check = ratios[ratios.size() / 2];
  }
  return r;
}

}  // namespace rgnav::vision::eval
