#include "vision/dense_stereo.h"

#include <opencv2/imgproc.hpp>

namespace rgnav::vision {

namespace {

int sgbm_mode(const std::string& mode)
{
  if (mode == "hh") return cv::StereoSGBM::MODE_HH;
  if (mode == "sgbm_3way") return cv::StereoSGBM::MODE_SGBM_3WAY;
  if (mode == "hh4") return cv::StereoSGBM::MODE_HH4;
  return cv::StereoSGBM::MODE_SGBM;
}

}  // namespace

DenseStereo::DenseStereo(const DisparityOptions& options) : options_(options)
{
  const int b = options.block_size;
  sgbm_ = cv::StereoSGBM::create(options.min_disparity, options.num_disparities, b, options.p1 > 0 ? options.p1 : 8 * b * b,
                                 options.p2 > 0 ? options.p2 : 32 * b * b, options.disp12_max_diff, options.pre_filter_cap,
                                 options.uniqueness_ratio, options.speckle_window_size, options.speckle_range,
                                 sgbm_mode(options.mode));
}

cv::Mat DenseStereo::disparity(const cv::Mat& left, const cv::Mat& right) const
{
  cv::Mat l = left, r = right;
  if (options_.downscale > 1) {
    const cv::Size small(left.cols / options_.downscale, left.rows / options_.downscale);
    cv::resize(left, l, small, 0, 0, cv::INTER_AREA);
    cv::resize(right, r, small, 0, 0, cv::INTER_AREA);
  }
  if (!options_.pad_left) {
    cv::Mat d;
    sgbm_->compute(l, r, d);
    return d;
  }
  // SGBM leaves the first min_disparity + num_disparities columns invalid (their search range
  // would leave the right image). Matching images widened on the left by that much gives those
  // columns a disparity wherever their match is inside the right image.
  const int pad = options_.min_disparity + options_.num_disparities;
  cv::Mat lp, rp, d;
  cv::copyMakeBorder(l, lp, 0, 0, pad, 0, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::copyMakeBorder(r, rp, 0, 0, pad, 0, cv::BORDER_CONSTANT, cv::Scalar(0));
  sgbm_->compute(lp, rp, d);
  return d.colRange(pad, d.cols).clone();
}

std::vector<Eigen::Vector3f> disparity_to_points(const cv::Mat& disparity16, const RectifiedCamera& camera,
                                                 const PointOptions& options)
{
  CV_Assert(disparity16.type() == CV_16S);
  std::vector<Eigen::Vector3f> out;
  const int stride = std::max(1, options.stride);
  out.reserve(static_cast<size_t>(disparity16.rows / stride + 1) * static_cast<size_t>(disparity16.cols / stride + 1));
  const double fb = camera.focal * camera.baseline;
  // Disparity bounds from the depth bounds, in 1/16 px: one comparison per pixel.
  const double d_min = 16.0 * fb / options.max_depth;
  const double d_max = 16.0 * fb / options.min_depth;
  const float inv_f = static_cast<float>(1.0 / camera.focal);
  for (int v = 0; v < disparity16.rows; v += stride) {
    const int16_t* row = disparity16.ptr<int16_t>(v);
    for (int u = 0; u < disparity16.cols; u += stride) {
      const int16_t d = row[u];
      if (d <= 0 || d < d_min || d > d_max) continue;
      const float z = static_cast<float>(16.0 * fb / d);
      out.emplace_back((static_cast<float>(u) - static_cast<float>(camera.cx)) * z * inv_f,
                       (static_cast<float>(v) - static_cast<float>(camera.cy)) * z * inv_f, z);
    }
  }
  return out;
}

}  // namespace rgnav::vision
