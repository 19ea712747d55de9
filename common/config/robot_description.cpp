#include "config/robot_description.h"

#include <filesystem>
#include <vector>

namespace rgnav::config {
namespace {

// x [m], y [m], theta [rad], as every pose in config/.
geometry::Pose2 required_pose(const Config& c, const std::string& key)
{
  if (!c.has(key)) c.fail(key, "required pose missing");
  const auto v = c.numbers(key, {}, -10.0, 10.0, 3, 3);
  return geometry::Pose2(v[0], v[1], v[2]);
}

}  // namespace

RobotDescription load_robot_description(const Config& cfg)
{
  RobotDescription r;
  const auto robot = cfg.section("robot");
  r.name = robot.required_string("name");
  r.radius = robot.required_number("radius_m", 0.05, 2.0);
  r.height = robot.required_number("height_m", 0.1, 5.0);
  const auto drive = robot.section("drive");
  r.drive.kind = drive.choice("kind", r.drive.kind, {"synchro"});
  r.drive.max_v = drive.required_number("max_v_mps", 0.01, 10.0);
  r.drive.max_omega = drive.required_number("max_omega_radps", 0.01, 20.0);
  r.drive.max_accel = drive.required_number("max_accel_mps2", 0.01, 20.0);
  r.drive.max_alpha = drive.required_number("max_alpha_radps2", 0.01, 50.0);

  const auto laser = cfg.section("laser_front");
  r.laser_front.base_from_laser = required_pose(laser, "base_from_laser");
  r.laser_front.height = laser.required_number("mount_height_m", 0.0, 5.0);

  const auto stereo = cfg.section("stereo");
  r.stereo.base_from_head = required_pose(stereo, "base_from_head");
  r.stereo.height = stereo.required_number("head_height_m", 0.0, 5.0);
  r.stereo.baseline = stereo.required_number("baseline_m", 0.01, 2.0);
  return r;
}

RobotDescription load_robot_description_file(const std::string& path)
{
  const auto cfg = Config::load(path);
  const auto robot = load_robot_description(cfg);
  cfg.finish();
  return robot;
}

std::string robot_path_beside(const std::string& config_path, const std::string& fallback)
{
  const auto beside = std::filesystem::path(config_path).parent_path() / "robot.yaml";
  return std::filesystem::exists(beside) ? beside.string() : fallback;
}

}  // namespace rgnav::config
