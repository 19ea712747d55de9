#include "drivers/stereo/stereo_capture_node.h"

#include <spdlog/spdlog.h>

#include "rgnav/heartbeat_t.hpp"
#include "rgnav/stereo_images_t.hpp"

namespace rgnav::stereo {

CaptureOptions load_capture_options(const config::Config& c, const config::Config& channels, const std::string& data_root)
{
  CaptureOptions o;
  o.source = c.choice("source", "folder", {"folder", "cameras"}) == "cameras" ? CaptureOptions::Source::kCameras
                                                                            : CaptureOptions::Source::kFolder;
  const auto cams = c.section("cameras");
  o.cameras.left_device = cams.string("left_device", o.cameras.left_device);
  o.cameras.right_device = cams.string("right_device", o.cameras.right_device);
  o.cameras.width = static_cast<int>(cams.integer("width", o.cameras.width, 16, 8192));
  o.cameras.height = static_cast<int>(cams.integer("height", o.cameras.height, 16, 8192));
  const auto folder = c.section("folder");
  o.folder.folder = folder.string("path", "stereo/chessboard");
  if (!o.folder.folder.empty() && o.folder.folder[0] != '/') o.folder.folder = data_root + "/" + o.folder.folder;
  o.folder.left_token = folder.string("left_token", o.folder.left_token);
  o.folder.right_token = folder.string("right_token", o.folder.right_token);
  if (o.folder.left_token.empty() || o.folder.left_token == o.folder.right_token)
    folder.fail("right_token", "left and right tokens must be non-empty and differ");
  o.folder.loop = folder.boolean("loop", o.folder.loop);
  const bool gray = c.boolean("grayscale", false);
  o.folder.grayscale = o.cameras.grayscale = gray;
  o.encoding = c.choice("encoding", "jpeg", {"jpeg", "raw"}) == "raw" ? Encoding::kRaw : Encoding::kJpeg;
  o.jpeg_quality = static_cast<int>(c.integer("jpeg_quality", o.jpeg_quality, 1, 100));
  o.rate_hz = c.number("rate_hz", o.rate_hz, 0.1, 60);
  o.cameras.fps = o.rate_hz;
  o.calibration_id = c.string("calibration_id", o.calibration_id);
  o.pan = c.number("pan_rad", 0, -M_PI, M_PI);
  o.tilt = c.number("tilt_rad", 0, -M_PI / 2, M_PI / 2);
  o.channel = channels.string("stereo", o.channel);
  return o;
}

std::unique_ptr<StereoSource> make_source(const CaptureOptions& o)
{
  if (o.source == CaptureOptions::Source::kCameras) return std::make_unique<CameraPairSource>(o.cameras);
  return std::make_unique<ImageFolderSource>(o.folder);
}

StereoCaptureNode::StereoCaptureNode(runtime::Node& node, CaptureOptions options, std::unique_ptr<StereoSource> source)
    : node_(node), options_(std::move(options)), source_(std::move(source))
{
  spdlog::info("stereo capture from {} at {} Hz, {}", source_->describe(), options_.rate_hz,
               options_.encoding == Encoding::kJpeg ? "JPEG" : "raw");
  node_.every(std::chrono::microseconds(static_cast<int64_t>(1e6 / options_.rate_hz)), [this] { capture_once(); });
}

void StereoCaptureNode::capture_once()
{
  auto frame = source_->next();
  if (!frame) {
    ++failures_;
    node_.set_status(heartbeat_t::STATE_DEGRADED, "no frame: " + source_->error());
    return;
  }
  stereo_images_t m;
  m.utime = frame->utime;
  m.frame_id = ++frame_id_;
  m.calibration_id = options_.calibration_id;
  m.pan = options_.pan;
  m.tilt = options_.tilt;
  m.left = encode_image(frame->left, frame->utime, options_.encoding, options_.jpeg_quality);
  m.right = encode_image(frame->right, frame->utime, options_.encoding, options_.jpeg_quality);
  if (node_.publish(options_.channel, m)) node_.clear_status();
}

}  // namespace rgnav::stereo
