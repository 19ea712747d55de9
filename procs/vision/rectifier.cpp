#include "vision/rectifier.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace rgnav::vision {

namespace {

bool no_distortion(const cv::Mat& d) { return d.empty() || cv::countNonZero(d != 0.0) == 0; }

cv::Mat to_gray(const cv::Mat& m)
{
  if (m.channels() == 1) return m;
  cv::Mat g;
  cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
  return g;
}

}  // namespace

RectifiedCamera RectifiedCamera::scaled_down(int factor) const
{
  RectifiedCamera c = *this;
  const double s = 1.0 / factor;
  c.size = cv::Size(size.width / factor, size.height / factor);
  c.focal = focal * s;
  // Pixel centres: cv::resize(INTER_AREA) maps pixel i of the small image to i*f + (f-1)/2.
  c.cx = (cx - (factor - 1) / 2.0) * s;
  c.cy = (cy - (factor - 1) / 2.0) * s;
  return c;
}

Rectifier::Rectifier(const StereoRig& rig, double alpha)
{
  camera_.size = rig.image_size;
  const cv::Mat t = rig.T.reshape(1, 3);
  // A rig that is rectified already keeps its pixels as they are: remapping would only blur.
  const bool parallel = cv::norm(rig.R, cv::Mat::eye(3, 3, CV_64F), cv::NORM_INF) < 1e-9 &&
                        std::abs(t.at<double>(1)) < 1e-9 && std::abs(t.at<double>(2)) < 1e-9 && t.at<double>(0) < 0 &&
                        cv::norm(rig.M1, rig.M2, cv::NORM_INF) < 1e-9 && no_distortion(rig.D1) && no_distortion(rig.D2) &&
                        std::abs(rig.M1.at<double>(0, 0) - rig.M1.at<double>(1, 1)) < 1e-9;
  if (parallel) {
    identity_ = true;
    camera_.focal = rig.M1.at<double>(0, 0);
    camera_.cx = rig.M1.at<double>(0, 2);
    camera_.cy = rig.M1.at<double>(1, 2);
    camera_.baseline = -t.at<double>(0);
    return;
  }
  cv::Mat r1, r2, p1, p2, q;
  cv::stereoRectify(rig.M1, rig.D1, rig.M2, rig.D2, rig.image_size, rig.R, t, r1, r2, p1, p2, q, cv::CALIB_ZERO_DISPARITY,
                    alpha, rig.image_size);
  cv::initUndistortRectifyMap(rig.M1, rig.D1, r1, p1, rig.image_size, CV_16SC2, left_map1_, left_map2_);
  cv::initUndistortRectifyMap(rig.M2, rig.D2, r2, p2, rig.image_size, CV_16SC2, right_map1_, right_map2_);
  camera_.focal = p1.at<double>(0, 0);
  camera_.cx = p1.at<double>(0, 2);
  camera_.cy = p1.at<double>(1, 2);
  camera_.baseline = -p2.at<double>(0, 3) / p2.at<double>(0, 0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) camera_.camera_from_rectified(r, c) = r1.at<double>(c, r);   // R1 transposed
}

void Rectifier::rectify(const cv::Mat& left, const cv::Mat& right, cv::Mat* left_out, cv::Mat* right_out) const
{
  const cv::Mat l = to_gray(left), r = to_gray(right);
  if (identity_) {
    *left_out = l;
    *right_out = r;
    return;
  }
  cv::remap(l, *left_out, left_map1_, left_map2_, cv::INTER_LINEAR);
  cv::remap(r, *right_out, right_map1_, right_map2_, cv::INTER_LINEAR);
}

}  // namespace rgnav::vision
