// The SICK LMS 2xx as the simulator sees it: 180 degrees in 181 beams (1 deg, one scan per
// mirror turn, 75 Hz) or 361 beams (0.5 deg, two interlaced turns, 37.5 Hz); the 8 m mode
// reports millimetres, the 80 m mode centimetres; no return reads as the range maximum.
// Each beam is a ray cast at the mounting height, so only obstacles spanning that height
// are seen; Gaussian range noise is added before quantisation.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sensors/laser_scan.h"
#include "sim/rng.h"
#include "sim/scene.h"
#include "sim/world.h"

namespace rgnav::sim {

struct Lms2xxOptions
{
  std::string sensor = "laser_front";
  int beams = 181;             // 181 (1 deg) or 361 (0.5 deg)
  int range_mode_m = 8;        // 8 (mm resolution, max 8.183 m) or 80 (cm resolution, max 81.83 m)
  double noise_sigma = 0.01;   // [m] std of the Gaussian range noise
  double mount_x = 0.12;       // [m] laser position in the base frame
  double mount_y = 0.0;
  double mount_yaw = 0.0;      // [rad]
  double mount_height = 0.40;  // [m] height of the scan plane above the floor

  double angle_increment() const { return beams == 361 ? M_PI / 360.0 : M_PI / 180.0; }
  double resolution() const { return range_mode_m == 80 ? 0.01 : 0.001; }
  // The LMS 2xx codes "no return" with the largest values; 8183 units and up are errors.
  double range_max() const { return 8183.0 * resolution(); }
  double rate_hz() const { return beams == 361 ? 37.5 : 75.0; }
  double scan_time() const { return 1.0 / rate_hz(); }
};

struct Circle
{
  Vec2 center;
  double radius;
};

class Lms2xxModel
{
 public:
  Lms2xxModel(const Lms2xxOptions& options, Rng rng);

  // True ranges (no noise, no quantisation, infinity for no return) from the laser pose.
  std::vector<double> true_ranges(const Scene& scene, const std::vector<uint8_t>& door_open,
                                  const std::vector<Circle>& people, const Pose2& laser_pose) const;
  // A full measurement: noise, quantisation, max-range for no return.
  sensors::LaserScan measure(const Scene& scene, const std::vector<uint8_t>& door_open,
                             const std::vector<Circle>& people, const Pose2& base_pose, int64_t utime,
                             int64_t scan_id);

  Pose2 laser_pose(const Pose2& base_pose) const;
  const Lms2xxOptions& options() const { return options_; }

 private:
  const Lms2xxOptions options_;
  Rng rng_;
  std::vector<Vec2> directions_;  // beam directions in the laser frame
};

}  // namespace rgnav::sim
