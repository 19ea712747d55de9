// The rig's calibration from chessboard pairs (procs/vision/tools): on pairs drawn through a known
// rig it recovers the focal length and baseline; rgnav_stereo_calibrate on the shared chessboard
// pairs writes a file the product's loader takes, with a sane RMS; the checked-in
// config/stereo/chessboard_demo.yml (that tool's output) loads.
#include "chessboard_calibration.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "drivers/stereo/stereo_calibration.h"

namespace rgnav::vision::tools {
namespace {

// A chessboard of `inner` corners (squares of `square` m, a white margin of one square) at
// rvec/tvec in a pinhole camera K, drawn with anti-aliased edges on grey.
cv::Mat draw_board(cv::Size inner, double square, const cv::Vec3d& rvec, const cv::Vec3d& tvec, const cv::Matx33d& K)
{
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(110));
  const auto project = [&](const std::vector<cv::Point3f>& pts) {
    std::vector<cv::Point2f> px;
    cv::projectPoints(pts, rvec, tvec, K, cv::noArray(), px);
    std::vector<cv::Point> fixed;
    for (const auto& p : px) fixed.emplace_back(cvRound(p.x * 16), cvRound(p.y * 16));   // 4 fractional bits
    return fixed;
  };
  const auto quad = [&](double x0, double y0, double x1, double y1) {
    return std::vector<cv::Point3f>{{float(x0), float(y0), 0.f}, {float(x1), float(y0), 0.f}, {float(x1), float(y1), 0.f},
                                    {float(x0), float(y1), 0.f}};
  };
  // The board's white face: squares from -1 to inner (one margin square around them).
  cv::fillConvexPoly(img, project(quad(-2 * square, -2 * square, (inner.width + 1) * square, (inner.height + 1) * square)),
                     cv::Scalar(235), cv::LINE_AA, 4);
  for (int y = -1; y < inner.height; ++y)
    for (int x = -1; x < inner.width; ++x)
      if (((x + y) & 1) == 0)
        cv::fillConvexPoly(img, project(quad(x * square, y * square, (x + 1) * square, (y + 1) * square)), cv::Scalar(20),
                           cv::LINE_AA, 4);
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.6);
  return img;
}

TEST(StereoCalibrate, RecoversAKnownRigFromDrawnPairs)
{
  const cv::Matx33d K(500, 0, 320, 0, 500, 240, 0, 0, 1);
  const double baseline = 0.10, square = 0.03;
  const cv::Size inner(9, 6);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> tilt(-0.35, 0.35), dx(-0.08, 0.02), dy(-0.12, -0.04), dz(0.65, 0.95);
  std::vector<ChessboardPair> pairs;
  for (int i = 0; i < 10; ++i) {
    const cv::Vec3d rvec(tilt(rng), tilt(rng), 0.2 * tilt(rng));
    const cv::Vec3d tvec(dx(rng) - 0.1, dy(rng), dz(rng));
    const cv::Mat left = draw_board(inner, square, rvec, tvec, K);
    const cv::Mat right = draw_board(inner, square, rvec, tvec + cv::Vec3d(-baseline, 0, 0), K);  // X_r = X_l + T
    const auto cl = find_chessboard(left, inner), cr = find_chessboard(right, inner);
    if (cl && cr) pairs.push_back({"pair" + std::to_string(i), *cl, *cr});
  }
  ASSERT_GE(pairs.size(), 8u);
  ChessboardOptions o;
  o.inner_corners = inner;
  o.square_size = square;
  const auto r = calibrate_stereo(pairs, cv::Size(640, 480), o);
  EXPECT_LT(r.rms_px, 0.3);
  EXPECT_NEAR(r.calibration.M1(0, 0), 500.0, 5.0);
  EXPECT_NEAR(r.calibration.M2(1, 1), 500.0, 5.0);
  EXPECT_NEAR(r.calibration.baseline(), baseline, 0.002);
  EXPECT_LT(r.calibration.T[0], 0.0);   // the right camera to the right: X_right = X_left + T
  EXPECT_LT(r.epipolar_error_px, 0.3);
}

TEST(StereoCalibrate, RefusesTooFewPairsAndWrongCorners)
{
  ChessboardOptions o;
  EXPECT_THROW(calibrate_stereo({}, cv::Size(640, 480), o), std::invalid_argument);
  ChessboardPair bad{"bad", std::vector<cv::Point2f>(10), std::vector<cv::Point2f>(10)};
  EXPECT_THROW(calibrate_stereo({bad, bad, bad}, cv::Size(640, 480), o), std::invalid_argument);
}

TEST(StereoCalibrate, ToolOnTheSharedPairsWritesALoadableFileWithASaneRms)
{
  const std::string data = RGNAV_DATA_DIR "/stereo/chessboard";
  if (!std::filesystem::is_directory(data)) GTEST_SKIP() << data << " missing";
  const auto dir = std::filesystem::temp_directory_path() / ("rgnav_calib_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "rig.yml").string(), report = (dir / "report.json").string();
  const std::string cmd = std::string(RGNAV_CALIBRATE_BIN) + " --images " + data + " --out " + out + " --report " + report +
                          " --robot " RGNAV_SOURCE_DIR "/config/robot.yaml > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto c = stereo::load_stereo_calibration(out);
  EXPECT_EQ(c.image_size, cv::Size(640, 480));
  EXPECT_GT(c.baseline(), 0.03);
  EXPECT_LT(c.baseline(), 0.3);
  EXPECT_TRUE(c.has_distortion());
  const auto j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_GE(j["pairs"].get<int>(), 10);
  // Sub-pixel corners of a rigid board: OpenCV's sample reaches ~0.4 px on these pairs. Above a
  // pixel something is wrong (a pair mismatched, the board size wrong).
  EXPECT_GT(j["calib_reprojection_px"].get<double>(), 0.0);
  EXPECT_LT(j["calib_reprojection_px"].get<double>(), 1.0);
  std::filesystem::remove_all(dir);
}

TEST(StereoCalibrate, TheCheckedInRealRigCalibrationLoads)
{
  const auto c = stereo::load_stereo_calibration(RGNAV_SOURCE_DIR "/config/stereo/chessboard_demo.yml");
  EXPECT_EQ(c.image_size, cv::Size(640, 480));
  EXPECT_GT(c.baseline(), 0.03);
  EXPECT_LT(c.baseline(), 0.3);
}

TEST(StereoCalibrationFile, WhatIsWrittenLoadsBackTheSame)
{
  stereo::StereoCalibration c = stereo::load_stereo_calibration(RGNAV_SOURCE_DIR "/config/stereo/sim_b21r_head.yml");
  c.D1 = (cv::Mat_<double>(1, 5) << -0.2, 0.05, 0.001, -0.002, 0.0);
  const auto path = std::filesystem::temp_directory_path() / ("rgnav_calib_rt_" + std::to_string(::getpid()) + ".yml");
  stereo::write_stereo_calibration(path.string(), c, "a comment\n\nover lines");
  const auto back = stereo::load_stereo_calibration(path.string());
  EXPECT_EQ(back.image_size, c.image_size);
  EXPECT_EQ(cv::norm(back.M1, c.M1), 0.0);
  EXPECT_EQ(cv::norm(back.D1, c.D1), 0.0);
  EXPECT_EQ(cv::norm(back.T, c.T), 0.0);
  EXPECT_EQ(back.base_from_head, c.base_from_head);
  EXPECT_EQ(back.head_from_left_camera_xyz, c.head_from_left_camera_xyz);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rgnav::vision::tools
