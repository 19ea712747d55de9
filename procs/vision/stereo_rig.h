// The stereo rig as the vision library sees it: the two cameras' calibration in OpenCV's
// stereo_calib conventions and where the left camera sits on the pan-tilt head. The node fills
// it from the calibration file (drivers/stereo/stereo_calibration.h); the library takes plain
// numbers so that it can be tested without files or a bus.
//
// Frames: base (x forward, y left, z up, on the floor); head = the pan-tilt unit's centre, axes
// as the base's at pan = tilt = 0; camera = OpenCV's optical frame (x right, y down, z forward).
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace rgnav::vision {

struct StereoRig
{
  cv::Size image_size;      // [px] both cameras
  cv::Mat M1, D1, M2, D2;   // intrinsics (3x3) and distortion (1xN) of left and right, CV_64F
  cv::Mat R, T;             // right camera w.r.t. left: x_right = R * x_left + T, T in metres
  // Pan-tilt unit centre in the base frame at pan = tilt = 0 (translation only in practice).
  Eigen::Isometry3d base_from_head = Eigen::Isometry3d::Identity();
  // Left camera's optical frame on the head (fixed; at pan = tilt = 0).
  Eigen::Isometry3d head_from_camera = Eigen::Isometry3d::Identity();
};

// The optical frame (z forward, x right, y down) of a camera looking along the head's x axis.
Eigen::Isometry3d optical_from_forward();

// Left camera in the base frame for a head at `pan` (about z, CCW +) and `tilt` (+ = looking
// up, about the panned y axis).
Eigen::Isometry3d base_from_camera(const StereoRig& rig, double pan, double tilt);

// An ideal rectified rig (no distortion, R = I, T = -baseline along x): synthetic tests and
// benches that shift a texture by f*B/Z.
StereoRig ideal_rig(cv::Size size, double focal_px, double baseline_m);

// Empty if the rig is usable, else what is wrong with it (sizes, matrix shapes, a baseline of 0).
std::string check_rig(const StereoRig& rig);

}  // namespace rgnav::vision
