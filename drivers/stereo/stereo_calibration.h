// The stereo rig's calibration: both cameras' intrinsics and distortion, the right camera's pose
// from the left one, and where the rig sits on the pan-tilt head and the head on the robot. One
// file per rig, config/stereo/<calibration_id>.yml, in OpenCV FileStorage YAML as OpenCV's
// stereo_calib sample writes it plus the mounting keys (config/stereo/sim_b21r_head.yml names
// every field). Read by whatever renders or consumes STEREO_IMAGES (the simulated head, vision).
//
// Frames: base = robot base (drive centre on the floor, x forward, y left, z up); head = the
// pan-tilt centre, base axes turned by pan about z (CCW +) then by tilt about the turned y axis
// (+ = looking up); camera = OpenCV optical frame (x right, y down, z along the optical axis).
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <string>

namespace rgnav::stereo {

struct StereoCalibration
{
  std::string source;   // file it came from (messages)
  cv::Size image_size;  // [px]
  cv::Matx33d M1, M2;   // camera matrices [px]
  cv::Mat D1, D2;       // distortion, 1xN CV_64F (N = 4, 5, 8, 12 or 14), OpenCV's model
  cv::Matx33d R;        // right from left: X_right = R * X_left + T
  cv::Vec3d T;          // [m]
  Eigen::Vector3d base_from_head{0, 0, 0};            // [m] head centre in the base frame
  Eigen::Vector3d head_from_left_camera_xyz{0, 0, 0}; // [m] left optical centre in the head frame
  Eigen::Vector3d head_from_left_camera_rpy{0, 0, 0}; // [rad] beyond the nominal mounting

  double baseline() const { return cv::norm(T); }  // [m]
  bool has_distortion() const { return cv::countNonZero(D1) > 0 || cv::countNonZero(D2) > 0; }
};

// Reads and checks a calibration file. Throws config::ConfigError naming the file (and the key
// when one is at fault) when the file is missing, empty, binary or not OpenCV YAML, a required
// key is missing, a key is unknown, or a value is out of range: camera matrices with positive
// focal lengths and the principal point inside the image, finite distortion of a size OpenCV
// takes, R a rotation, a baseline within (0.01, 2] m, mounting within 5 m of the base.
StereoCalibration load_stereo_calibration(const std::string& path);

// The optional rectification keys stereo_calib writes beside the calibration (cv::stereoRectify's
// outputs); empty matrices are left out.
struct StereoRectification
{
  cv::Mat R1, R2, P1, P2, Q;
};

// The file load_stereo_calibration reads, as text: "%YAML:1.0", `comment` (every line made a
// '#' comment), then the keys. Atomic write to `path` (a temporary file renamed); throws
// std::runtime_error when it cannot be written.
std::string stereo_calibration_text(const StereoCalibration& c, const std::string& comment,
                                    const StereoRectification& rectification = {});
void write_stereo_calibration(const std::string& path, const StereoCalibration& c, const std::string& comment,
                              const StereoRectification& rectification = {});

// <config_dir>/stereo/<calibration_id>.yml. Throws config::ConfigError for an id that is empty
// or not a plain name (letters, digits, '_', '-', '.'; no path separators).
std::string stereo_calibration_path(const std::string& config_dir, const std::string& calibration_id);

// The nominal mounting: camera axes (x right, y down, z forward) in the head frame's axes.
Eigen::Matrix3d head_from_optical_nominal();
// Pose of the left camera (optical frame) in the base frame at the given head angles.
Eigen::Isometry3d base_from_left_camera(const StereoCalibration& c, double pan, double tilt);
// Pose of the right camera in the left camera's frame (from R, T).
Eigen::Isometry3d left_from_right_camera(const StereoCalibration& c);

}  // namespace rgnav::stereo
