// stereo_capture: grabs stereo pairs at a fixed rate from a StereoSource and publishes
// STEREO_IMAGES (raw or JPEG, with capture time and calibration id).
#pragma once

#include <memory>
#include <string>

#include "config/config.h"
#include "drivers/stereo/camera_pair_source.h"
#include "drivers/stereo/image_encoding.h"
#include "drivers/stereo/image_folder_source.h"
#include "runtime/node.h"

namespace rgnav::stereo {

// The simulated head (drivers/sim/sim_stereo_source.h): what it renders and where the true pose
// comes from.
struct SimSourceOptions
{
  std::string world_file;        // the simulator's world (the same as sim.yaml's sim.world)
  std::string calibration_file;  // <config dir>/stereo/<calibration_id>.yml
  std::string truth_channel = "SIM_TRUTH";
  double noise_sigma = 2.0;      // [grey levels]
  int64_t noise_seed = 1;
  int64_t people_seed = 1;       // the simulator's seed (sim.yaml sim.seed)
};

struct CaptureOptions
{
  enum class Source { kCameras, kFolder, kSim } source = Source::kFolder;
  CameraPairOptions cameras;
  ImageFolderOptions folder;
  SimSourceOptions sim;
  Encoding encoding = Encoding::kJpeg;
  int jpeg_quality = 90;
  double rate_hz = 10;
  std::string calibration_id = "b21r_head";
  double pan = 0, tilt = 0;    // [rad] fixed head angles until a pan-tilt driver reports them
  std::string channel = "STEREO_IMAGES";
};

// A world name (config/worlds/<name>.yaml) or a file (relative paths: the config folder).
std::string world_path(const std::string& world, const std::string& config_dir);

// data_root resolves relative folder paths (the repository's ../shared/data by default);
// config_dir the calibration file and the simulated world (source: sim), which must exist.
CaptureOptions load_capture_options(const config::Config& capture, const config::Config& channels,
                                    const std::string& data_root, const std::string& config_dir);
// Cameras or folder; the simulated head needs the bus for the true pose and is made by
// drivers/sim (sim_stereo_feed.h).
std::unique_ptr<StereoSource> make_source(const CaptureOptions& options);

class StereoCaptureNode
{
 public:
  StereoCaptureNode(runtime::Node& node, CaptureOptions options, std::unique_ptr<StereoSource> source);
  // One capture (called by the node's timer; public for tests).
  void capture_once();
  int64_t frames() const { return frame_id_; }
  int64_t failures() const { return failures_; }

 private:
  runtime::Node& node_;
  const CaptureOptions options_;
  std::unique_ptr<StereoSource> source_;
  int64_t frame_id_ = 0;
  int64_t failures_ = 0;
};

}  // namespace rgnav::stereo
