#include "vision/stereo_rig.h"

#include <cmath>
#include <string>

namespace rgnav::vision {

Eigen::Isometry3d optical_from_forward()
{
  // Columns: the optical axes x (right = -y), y (down = -z), z (forward = x) in head axes.
  Eigen::Matrix3d r;
  r << 0, 0, 1,
      -1, 0, 0,
       0, -1, 0;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  return t;
}

Eigen::Isometry3d base_from_camera(const StereoRig& rig, double pan, double tilt)
{
  // Tilting up turns the x axis towards +z: a rotation by -tilt about y.
  const Eigen::Isometry3d pan_tilt(Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitY()));
  return rig.base_from_head * pan_tilt * rig.head_from_camera;
}

StereoRig ideal_rig(cv::Size size, double focal_px, double baseline_m)
{
  StereoRig rig;
  rig.image_size = size;
  rig.M1 = (cv::Mat_<double>(3, 3) << focal_px, 0, (size.width - 1) / 2.0, 0, focal_px, (size.height - 1) / 2.0, 0, 0, 1);
  rig.M2 = rig.M1.clone();
  rig.D1 = cv::Mat::zeros(1, 5, CV_64F);
  rig.D2 = cv::Mat::zeros(1, 5, CV_64F);
  rig.R = cv::Mat::eye(3, 3, CV_64F);
  rig.T = (cv::Mat_<double>(3, 1) << -baseline_m, 0, 0);
  rig.head_from_camera = optical_from_forward();
  return rig;
}

std::string check_rig(const StereoRig& rig)
{
  if (rig.image_size.width < 16 || rig.image_size.height < 16) return "image size below 16x16 px";
  const auto is = [](const cv::Mat& m, int rows, int cols) { return m.rows == rows && m.cols == cols && m.type() == CV_64F; };
  if (!is(rig.M1, 3, 3) || !is(rig.M2, 3, 3)) return "M1 and M2 must be 3x3 (CV_64F)";
  if (!is(rig.R, 3, 3)) return "R must be 3x3 (CV_64F)";
  if (!is(rig.T, 3, 1) && !is(rig.T, 1, 3)) return "T must have 3 elements (CV_64F)";
  const auto distortion_ok = [](const cv::Mat& d) {
    return d.empty() || (d.type() == CV_64F && (d.rows == 1 || d.cols == 1) && d.total() >= 4 && d.total() <= 14);
  };
  if (!distortion_ok(rig.D1) || !distortion_ok(rig.D2)) return "D1 and D2 must have 4 to 14 elements (CV_64F)";
  if (!(rig.M1.at<double>(0, 0) > 0 && rig.M1.at<double>(1, 1) > 0 && rig.M2.at<double>(0, 0) > 0 && rig.M2.at<double>(1, 1) > 0))
    return "focal lengths must be positive";
  if (!(cv::norm(rig.T) > 1e-3)) return "baseline |T| below 1 mm";
  if (!rig.base_from_head.matrix().allFinite() || !rig.head_from_camera.matrix().allFinite()) return "head mounting not finite";
  return {};
}

}  // namespace rgnav::vision
