#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "bad_files.h"
#include "child_process.h"
#include "config/config.h"
#include "drivers/stereo/stereo_calibration.h"

namespace rgnav::stereo {
namespace {

const std::string kSimRig = std::string(RGNAV_SOURCE_DIR) + "/config/stereo/sim_b21r_head.yml";

TEST(StereoCalibration, ShippedSimRigLoads)
{
  const auto c = load_stereo_calibration(kSimRig);
  EXPECT_EQ(c.image_size, cv::Size(640, 480));
  EXPECT_DOUBLE_EQ(c.M1(0, 0), 500.0);
  EXPECT_NEAR(c.baseline(), 0.12, 1e-12);
  EXPECT_FALSE(c.has_distortion());
  EXPECT_EQ(stereo_calibration_path(std::string(RGNAV_SOURCE_DIR) + "/config", "sim_b21r_head"), kSimRig);
}

TEST(StereoCalibration, CameraPosesOnTheHead)
{
  const auto c = load_stereo_calibration(kSimRig);
  // Head straight: the left camera looks along base x from 1.25 m, 6 cm left of the centre line.
  const Eigen::Isometry3d left = base_from_left_camera(c, 0.0, 0.0);
  EXPECT_NEAR(left.translation().z(), 1.25, 1e-9);
  EXPECT_NEAR(left.translation().y(), 0.06, 1e-9);
  EXPECT_NEAR((left.linear() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  // The right camera is 12 cm to the right (base -y), at the same height.
  const Eigen::Isometry3d right = left * left_from_right_camera(c);
  EXPECT_NEAR(right.translation().y(), -0.06, 1e-9);
  EXPECT_NEAR(right.translation().z(), 1.25, 1e-9);
  // Pan +90 degrees looks left; tilt + looks up.
  const Eigen::Vector3d axis_left = base_from_left_camera(c, M_PI / 2, 0.0).linear() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR((axis_left - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  const Eigen::Vector3d axis_up = base_from_left_camera(c, 0.0, 0.3).linear() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(axis_up.z(), std::sin(0.3), 1e-12);
}

// Each edit of the shipped file that makes it wrong is refused, naming the file and the key.
TEST(StereoCalibration, BadValuesRefusedNamingFileAndKey)
{
  testing::TempDir dir("stereo_calib");
  const std::string good = testing::read_file(kSimRig);
  struct Case { std::string from, to, key; };
  const std::vector<Case> cases = {
      {"image_width: 640", "image_width: 0", "image_width"},
      {"image_height: 480\n", "", "image_height"},
      {"data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. ]", "data: [ -500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. ]", "M1"},
      {"data: [ 0., 0., 0., 0., 0. ]", "data: [ 0., 0., .nan, 0., 0. ]", "D1"},
      {"data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]", "data: [ 1., 0., 0., 0., 2., 0., 0., 0., 1. ]", "R"},
      {"data: [ -0.12, 0., 0. ]", "data: [ -120., 0., 0. ]", "T"},
      {"data: [ 0.05, 0., 1.2 ]", "data: [ 0.05, 0. ]", "base_from_head"},
      {"image_width: 640", "image_width: 640\nimage_widht: 640", "image_widht"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.key);
    std::string text = good;
    const auto at = text.find(k.from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, k.from.size(), k.to);
    const std::string path = dir.file("calib.yml");
    testing::write_bytes(path, text);
    try {
      load_stereo_calibration(path);
      ADD_FAILURE() << "accepted";
    } catch (const config::ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("'" + k.key + "'"), std::string::npos) << what;
    }
  }
}

TEST(StereoCalibration, RandomEmptyAndCutOffFilesRefused)
{
  testing::TempDir dir("stereo_calib_bad");
  for (const auto& f : testing::write_bad_files(dir.path(), "calib.yml", testing::read_file(kSimRig))) {
    SCOPED_TRACE(f.kind);
    try {
      load_stereo_calibration(f.path);
      ADD_FAILURE() << "accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(f.path), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(load_stereo_calibration(dir.file("missing.yml")), config::ConfigError);
}

TEST(StereoCalibration, IdsArePlainNames)
{
  EXPECT_THROW(stereo_calibration_path("/c", "../secret"), config::ConfigError);
  EXPECT_THROW(stereo_calibration_path("/c", ""), config::ConfigError);
  EXPECT_EQ(stereo_calibration_path("/c", "b21r_head"), "/c/stereo/b21r_head.yml");
}

}  // namespace
}  // namespace rgnav::stereo
