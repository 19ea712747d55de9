#include "vision/rig_from_calibration.h"

namespace rgnav::vision {

StereoRig rig_from_calibration(const stereo::StereoCalibration& c)
{
  StereoRig rig;
  rig.image_size = c.image_size;
  rig.M1 = cv::Mat(c.M1, true);
  rig.M2 = cv::Mat(c.M2, true);
  rig.D1 = c.D1.clone();
  rig.D2 = c.D2.clone();
  rig.R = cv::Mat(c.R, true);
  rig.T = cv::Mat(c.T, true).reshape(1, 3);
  rig.base_from_head = Eigen::Isometry3d::Identity();
  rig.base_from_head.translation() = c.base_from_head;
  // The camera on the head: the calibration's own kinematics at pan = tilt = 0, less the head.
  rig.head_from_camera = rig.base_from_head.inverse() * stereo::base_from_left_camera(c, 0.0, 0.0);
  return rig;
}

}  // namespace rgnav::vision
