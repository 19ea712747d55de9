#include "chessboard_calibration.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <stdexcept>

namespace rgnav::vision::tools {

namespace {

std::vector<cv::Point3f> board_points(const ChessboardOptions& o)
{
  std::vector<cv::Point3f> p;
  for (int y = 0; y < o.inner_corners.height; ++y)
    for (int x = 0; x < o.inner_corners.width; ++x)
      p.emplace_back(static_cast<float>(x * o.square_size), static_cast<float>(y * o.square_size), 0.f);
  return p;
}

cv::Mat row(const cv::Mat& m) { return m.reshape(1, 1).clone(); }

double epipolar_error(const std::vector<ChessboardPair>& pairs, const StereoCalibrationResult& r, const cv::Mat& F)
{
  const auto& c = r.calibration;
  double sum = 0;
  size_t n = 0;
  for (const auto& p : pairs) {
    std::vector<cv::Point2f> l, rt;
    cv::undistortPoints(p.left, l, cv::Mat(c.M1), c.D1, cv::noArray(), cv::Mat(c.M1));
    cv::undistortPoints(p.right, rt, cv::Mat(c.M2), c.D2, cv::noArray(), cv::Mat(c.M2));
    std::vector<cv::Vec3f> lines_l, lines_r;
    cv::computeCorrespondEpilines(l, 1, F, lines_r);
    cv::computeCorrespondEpilines(rt, 2, F, lines_l);
    for (size_t i = 0; i < l.size(); ++i) {
      sum += std::abs(rt[i].x * lines_r[i][0] + rt[i].y * lines_r[i][1] + lines_r[i][2]) +
             std::abs(l[i].x * lines_l[i][0] + l[i].y * lines_l[i][1] + lines_l[i][2]);
      n += 2;
    }
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace

std::optional<std::vector<cv::Point2f>> find_chessboard(const cv::Mat& grey, cv::Size inner_corners)
{
  std::vector<cv::Point2f> corners;
  const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE;
  if (!cv::findChessboardCorners(grey, inner_corners, corners, flags)) return std::nullopt;
  cv::cornerSubPix(grey, corners, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
  return corners;
}

StereoCalibrationResult calibrate_stereo(const std::vector<ChessboardPair>& pairs, cv::Size image_size,
                                         const ChessboardOptions& options)
{
  if (pairs.size() < 3) throw std::invalid_argument("stereo calibration needs at least 3 pairs, got " + std::to_string(pairs.size()));
  const auto board = board_points(options);
  std::vector<std::vector<cv::Point3f>> object;
  std::vector<std::vector<cv::Point2f>> left, right;
  for (const auto& p : pairs) {
    if (p.left.size() != board.size() || p.right.size() != board.size())
      throw std::invalid_argument(p.name + ": " + std::to_string(p.left.size()) + "/" + std::to_string(p.right.size()) +
                                  " corners, the board has " + std::to_string(board.size()));
    object.push_back(board);
    left.push_back(p.left);
    right.push_back(p.right);
  }
  StereoCalibrationResult r;
  r.pairs = static_cast<int>(pairs.size());
  cv::Mat M1, D1, M2, D2, R, T, E, F;
  std::vector<cv::Mat> rv, tv;
  // Each camera alone first: a joint fit from a poor start converges to a worse minimum.
  r.left_rms_px = cv::calibrateCamera(object, left, image_size, M1, D1, rv, tv);
  r.right_rms_px = cv::calibrateCamera(object, right, image_size, M2, D2, rv, tv);
  r.rms_px = cv::stereoCalibrate(object, left, right, M1, D1, M2, D2, image_size, R, T, E, F, cv::CALIB_USE_INTRINSIC_GUESS,
                                 cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6));
  stereo::StereoCalibration& c = r.calibration;
  c.image_size = image_size;
  c.M1 = cv::Matx33d(M1);
  c.M2 = cv::Matx33d(M2);
  c.D1 = row(D1);
  c.D2 = row(D2);
  c.R = cv::Matx33d(R);
  c.T = cv::Vec3d(T.at<double>(0), T.at<double>(1), T.at<double>(2));
  cv::stereoRectify(M1, D1, M2, D2, image_size, R, T, r.R1, r.R2, r.P1, r.P2, r.Q, cv::CALIB_ZERO_DISPARITY, 0.0);
  r.epipolar_error_px = epipolar_error(pairs, r, F);
  return r;
}

}  // namespace rgnav::vision::tools
