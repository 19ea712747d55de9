// The vision's StereoRig from the rig's calibration file (drivers/stereo/stereo_calibration.h),
// with the head kinematics that file documents.
#pragma once

#include "drivers/stereo/stereo_calibration.h"
#include "vision/stereo_rig.h"

namespace rgnav::vision {

StereoRig rig_from_calibration(const stereo::StereoCalibration& c);

}  // namespace rgnav::vision
