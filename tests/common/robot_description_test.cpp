#include "config/robot_description.h"

#include <gtest/gtest.h>

#include <string>

#include "bad_files.h"

namespace rgnav::config {
namespace {

const char* const kGood = R"(robot:
  name: b21r
  radius_m: 0.3
  height_m: 1.4
  drive:
    kind: synchro
    max_v_mps: 1.0
    max_omega_radps: 1.5
    max_accel_mps2: 0.5
    max_alpha_radps2: 2.5
laser_front:
  base_from_laser: [0.2, -0.05, 0.1]
  mount_height_m: 0.35
stereo:
  base_from_head: [0.01, 0.0, 0.0]
  head_height_m: 1.3
  baseline_m: 0.1
)";

std::string error_of(const std::string& yaml)
{
  try {
    const auto cfg = Config::parse(yaml, "robot_test.yaml");
    load_robot_description(cfg);
    cfg.finish();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(RobotDescription, LoadsEveryValue)
{
  const auto cfg = Config::parse(kGood, "robot_test.yaml");
  const RobotDescription r = load_robot_description(cfg);
  EXPECT_NO_THROW(cfg.finish());
  EXPECT_EQ(r.name, "b21r");
  EXPECT_DOUBLE_EQ(r.radius, 0.3);
  EXPECT_DOUBLE_EQ(r.height, 1.4);
  EXPECT_EQ(r.drive.kind, "synchro");
  EXPECT_DOUBLE_EQ(r.drive.max_v, 1.0);
  EXPECT_DOUBLE_EQ(r.drive.max_omega, 1.5);
  EXPECT_DOUBLE_EQ(r.drive.max_accel, 0.5);
  EXPECT_DOUBLE_EQ(r.drive.max_alpha, 2.5);
  EXPECT_DOUBLE_EQ(r.laser_front.base_from_laser.x(), 0.2);
  EXPECT_DOUBLE_EQ(r.laser_front.base_from_laser.y(), -0.05);
  EXPECT_DOUBLE_EQ(r.laser_front.base_from_laser.theta(), 0.1);
  EXPECT_DOUBLE_EQ(r.laser_front.height, 0.35);
  EXPECT_DOUBLE_EQ(r.stereo.base_from_head.x(), 0.01);
  EXPECT_DOUBLE_EQ(r.stereo.height, 1.3);
  EXPECT_DOUBLE_EQ(r.stereo.baseline, 0.1);
}

TEST(RobotDescription, TheShippedFileIsValidAndTheStructDefaultsAreIt)
{
  // The option structs' defaults (tests, tools without a config) describe the same robot.
  const RobotDescription shipped = load_robot_description_file(RGNAV_SOURCE_DIR "/config/robot.yaml");
  const RobotDescription defaults;
  EXPECT_EQ(shipped.name, defaults.name);
  EXPECT_EQ(shipped.radius, defaults.radius);
  EXPECT_EQ(shipped.height, defaults.height);
  EXPECT_EQ(shipped.drive.max_v, defaults.drive.max_v);
  EXPECT_EQ(shipped.drive.max_omega, defaults.drive.max_omega);
  EXPECT_EQ(shipped.drive.max_accel, defaults.drive.max_accel);
  EXPECT_EQ(shipped.drive.max_alpha, defaults.drive.max_alpha);
  EXPECT_EQ(shipped.laser_front.base_from_laser.x(), defaults.laser_front.base_from_laser.x());
  EXPECT_EQ(shipped.laser_front.base_from_laser.y(), defaults.laser_front.base_from_laser.y());
  EXPECT_EQ(shipped.laser_front.base_from_laser.theta(), defaults.laser_front.base_from_laser.theta());
  EXPECT_EQ(shipped.laser_front.height, defaults.laser_front.height);
  EXPECT_EQ(shipped.stereo.height, defaults.stereo.height);
  EXPECT_EQ(shipped.stereo.baseline, defaults.stereo.baseline);
}

TEST(RobotDescription, AnUnknownKeyIsRefusedNamingFileAndKey)
{
  const std::string e = error_of(replaced(kGood, "  mount_height_m: 0.35\n", "  mount_height_m: 0.35\n  mount_hieght_m: 0.4\n"));
  EXPECT_NE(e.find("robot_test.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("laser_front.mount_hieght_m"), std::string::npos) << e;
}

TEST(RobotDescription, BadValuesAreRefusedNamingTheKey)
{
  const auto expect_error = [](const std::string& yaml, const std::string& key) {
    const std::string e = error_of(yaml);
    EXPECT_NE(e.find("robot_test.yaml"), std::string::npos) << e;
    EXPECT_NE(e.find(key), std::string::npos) << key << ": " << e;
  };
  expect_error(replaced(kGood, "radius_m: 0.3", "radius_m: -0.3"), "robot.radius_m");
  expect_error(replaced(kGood, "radius_m: 0.3", "radius_m: wide"), "robot.radius_m");
  expect_error(replaced(kGood, "max_v_mps: 1.0", "max_v_mps: 0"), "robot.drive.max_v_mps");
  expect_error(replaced(kGood, "kind: synchro", "kind: legs"), "robot.drive.kind");
  expect_error(replaced(kGood, "[0.2, -0.05, 0.1]", "[0.2, -0.05]"), "laser_front.base_from_laser");
  expect_error(replaced(kGood, "  base_from_laser: [0.2, -0.05, 0.1]\n", ""), "laser_front.base_from_laser");
  expect_error(replaced(kGood, "  baseline_m: 0.1\n", ""), "stereo.baseline_m");
}

TEST(RobotDescription, AMissingFileIsAnErrorNamingIt)
{
  try {
    load_robot_description_file("/nonexistent/robot.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/robot.yaml"), std::string::npos) << e.what();
  }
}

// Issue 35: random bytes, an empty file and one cut off inside a key are refused naming the file.
TEST(RobotDescription, RandomBytesEmptyAndCutOffFilesAreRefusedNamingThem)
{
  testing::TempDir dir("robot_bad");
  const std::string good(kGood);
  for (const auto& f : testing::write_bad_files(dir.path(), "robot.yaml", good, good.find("max_v_mps") + 3)) {
    SCOPED_TRACE(f.kind);
    try {
      load_robot_description_file(f.path);
      ADD_FAILURE() << f.path << " was loaded";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(f.path + ": ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace rgnav::config
