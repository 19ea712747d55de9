// Stereo calibration of a camera pair from chessboard views (what rgnav_stereo_calibrate does):
// corners found and refined to sub-pixel in each pair (both views must show the whole board),
// each camera calibrated on its own (cv::calibrateCamera: focal lengths, principal point, k1 k2 p1
// p2 k3), then both and the right camera's pose from the left refined together
// (cv::stereoCalibrate from those intrinsics), and the rectification cv::stereoRectify gives for
// them. The result is drivers/stereo/stereo_calibration.h's StereoCalibration, written in the
// format that loads it. The board's square size sets the scale: T comes out in its unit (metres).
#pragma once

#include <opencv2/core.hpp>

#include <optional>
#include <string>
#include <vector>

#include "drivers/stereo/stereo_calibration.h"

namespace rgnav::vision::tools {

struct ChessboardOptions
{
  cv::Size inner_corners{9, 6};   // corners where four squares meet, along the board's width and height
  double square_size = 0.025;     // [m]
};

struct ChessboardPair
{
  std::string name;                       // for messages (the left file)
  std::vector<cv::Point2f> left, right;   // the board's corners, the same order in both
};

struct StereoCalibrationResult
{
  stereo::StereoCalibration calibration;  // intrinsics, distortion, R, T (mounting left at zero)
  cv::Mat R1, R2, P1, P2, Q;              // cv::stereoRectify of the result (alpha 0)
  double rms_px = 0;                      // cv::stereoCalibrate's RMS reprojection error over both cameras
  double left_rms_px = 0, right_rms_px = 0;   // each camera's own calibration
  double epipolar_error_px = 0;           // mean distance of a corner from its partner's epipolar line
  int pairs = 0;
};

// The board's refined corners in one grey image, or nothing when the whole board is not found.
std::optional<std::vector<cv::Point2f>> find_chessboard(const cv::Mat& grey, cv::Size inner_corners);

// Throws std::invalid_argument with fewer than 3 pairs or corners that do not match the board.
StereoCalibrationResult calibrate_stereo(const std::vector<ChessboardPair>& pairs, cv::Size image_size,
                                         const ChessboardOptions& options);

}  // namespace rgnav::vision::tools
