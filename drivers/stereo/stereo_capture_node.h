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

struct CaptureOptions
{
  enum class Source { kCameras, kFolder } source = Source::kFolder;
  CameraPairOptions cameras;
  ImageFolderOptions folder;
  Encoding encoding = Encoding::kJpeg;
  int jpeg_quality = 90;
  double rate_hz = 10;
  std::string calibration_id = "b21r_head";
  double pan = 0, tilt = 0;    // [rad] fixed head angles until a pan-tilt driver reports them
  std::string channel = "STEREO_IMAGES";
};

// data_root resolves relative folder paths (the repository's ../shared/data by default).
CaptureOptions load_capture_options(const config::Config& capture, const config::Config& channels,
                                    const std::string& data_root);
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
