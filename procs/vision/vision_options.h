// Options of the vision process, as config/vision.yaml names them: channels, the calibration,
// frame handling, and the algorithm's options (vision_pipeline.h). The laser's mounting and
// height and the robot's height come from the robot description.
#pragma once

#include <string>

#include "geometry/pose2.h"
#include "vision/vision_pipeline.h"

namespace rgnav::config { class Config; struct RobotDescription; }

namespace rgnav::vision {

struct VisionChannels
{
  std::string stereo = "STEREO_IMAGES";
  std::string odometry = "ODOMETRY";
  std::string laser = "LASER_FRONT";
  std::string obstacles = "OBSTACLES_3D";
  std::string objects = "OBJECTS_3D";   // "" = no rectangles published
};

struct VisionNodeOptions
{
  VisionChannels channels;
  VisionOptions vision;
  std::string calibration_id = "sim_b21r_head";   // frames naming another calibration are dropped
  std::string calibration_file;                   // resolved path of config/stereo/<id>.yml
  geometry::Pose2 base_from_laser{0.12, 0.0, 0.0};
  double max_pose_gap = 0.2;     // [s] odometry on both sides of a capture within this, else the frame waits / is dropped
  double laser_period = 0.1;     // [s] laser scans fused at most this often (the laser runs at up to 75 Hz)
  int frame_queue = 2;           // STEREO_IMAGES LCM may hold while a frame is processed (older ones are dropped)
  int opencv_threads = 1;        // OpenCV's worker threads (1: the matcher keeps to one core of a shared machine)
  double stale_after = 2.0;      // [s] wall time without a processed frame before the status says so
};

// Reads the config's `channels`, `vision`, `disparity`, `points`, `map` and `rectangles` sections; a relative
// calibration path is resolved against the folder of `config_path`. Throws config::ConfigError
// naming file and key.
VisionNodeOptions load_vision_options(const config::Config& root, const config::RobotDescription& robot,
                                      const std::string& config_path);

}  // namespace rgnav::vision
