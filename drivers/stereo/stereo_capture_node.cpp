#include "drivers/stereo/stereo_capture_node.h"

#include <spdlog/spdlog.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "drivers/stereo/stereo_calibration.h"

#include "rgnav/heartbeat_t.hpp"
#include "rgnav/stereo_images_t.hpp"

namespace rgnav::stereo {

std::string world_path(const std::string& world, const std::string& config_dir)
{
  namespace fs = std::filesystem;
  if (world.find('/') == std::string::npos && fs::path(world).extension().empty())
    return config_dir + "/worlds/" + world + ".yaml";
  return fs::path(world).is_absolute() ? world : (fs::path(config_dir) / world).lexically_normal().string();
}

CaptureOptions load_capture_options(const config::Config& c, const config::Config& channels, const std::string& data_root,
                                    const std::string& config_dir)
{
  CaptureOptions o;
  const std::string source = c.choice("source", "folder", {"folder", "cameras", "sim"});
  o.source = source == "cameras" ? CaptureOptions::Source::kCameras
                                 : (source == "sim" ? CaptureOptions::Source::kSim : CaptureOptions::Source::kFolder);
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
  o.sim.truth_channel = channels.string("truth", o.sim.truth_channel);
  const auto sim = c.section("sim");
  o.sim.world_file = world_path(sim.string("world", "office"), config_dir);
  o.sim.noise_sigma = sim.number("noise_sigma", o.sim.noise_sigma, 0.0, 50.0);
  o.sim.noise_seed = sim.integer("noise_seed", o.sim.noise_seed, 0, INT64_MAX);
  o.sim.people_seed = sim.integer("people_seed", o.sim.people_seed, 0, INT64_MAX);
  if (o.source == CaptureOptions::Source::kSim) {
    // The images carry calibration_id; the simulated head renders through that very file.
    try {
      o.sim.calibration_file = stereo_calibration_path(config_dir, o.calibration_id);
    } catch (const config::ConfigError& e) {
      c.fail("calibration_id", e.what());
    }
    if (!std::filesystem::is_regular_file(o.sim.calibration_file))
      c.fail("calibration_id", "no calibration file " + o.sim.calibration_file);
    if (!std::filesystem::is_regular_file(o.sim.world_file)) sim.fail("world", "no world file " + o.sim.world_file);
  }
  return o;
}

std::unique_ptr<StereoSource> make_source(const CaptureOptions& o)
{
  if (o.source == CaptureOptions::Source::kSim)
    throw std::logic_error("the simulated head is made by sim::make_sim_stereo_source (drivers/sim)");
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
  // A grab (the simulated head renders two images) and each encoding take a while on a loaded
  // host: each step counts as progress, so the supervisor sees busy, not hung.
  node_.note_progress();
  stereo_images_t m;
  m.utime = frame->utime;
  m.frame_id = ++frame_id_;
  m.calibration_id = options_.calibration_id;
  m.pan = options_.pan;
  m.tilt = options_.tilt;
  m.left = encode_image(frame->left, frame->utime, options_.encoding, options_.jpeg_quality);
  node_.note_progress();
  m.right = encode_image(frame->right, frame->utime, options_.encoding, options_.jpeg_quality);
  if (node_.publish(options_.channel, m)) node_.clear_status();
}

}  // namespace rgnav::stereo
