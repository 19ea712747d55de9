#include "drivers/stereo/camera_pair_source.h"

#include <opencv2/imgproc.hpp>

#include <stdexcept>

#include "time/message_time.h"

namespace rgnav::stereo {
namespace {

void open_camera(cv::VideoCapture* cap, const CameraPairOptions& o, const std::string& device)
{
  if (!cap->open(device, cv::CAP_V4L2)) throw std::runtime_error("cannot open camera " + device + " (V4L2)");
  cap->set(cv::CAP_PROP_FRAME_WIDTH, o.width);
  cap->set(cv::CAP_PROP_FRAME_HEIGHT, o.height);
  cap->set(cv::CAP_PROP_FPS, o.fps);
  cap->set(cv::CAP_PROP_BUFFERSIZE, 1);  // newest frame, not a queue of old ones
}

}  // namespace

CameraPairSource::CameraPairSource(CameraPairOptions options) : options_(std::move(options))
{
  open_camera(&left_, options_, options_.left_device);
  open_camera(&right_, options_, options_.right_device);
}

std::optional<StereoFrame> CameraPairSource::next()
{
  StereoFrame f;
  f.utime = time::wall_utime();
  if (!left_.grab() || !right_.grab()) {
    error_ = "grab failed";
    return std::nullopt;
  }
  if (!left_.retrieve(f.left) || !right_.retrieve(f.right) || f.left.empty() || f.right.empty()) {
    error_ = "retrieve failed";
    return std::nullopt;
  }
  if (options_.grayscale) {
    cv::cvtColor(f.left, f.left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(f.right, f.right, cv::COLOR_BGR2GRAY);
  }
  return f;
}

std::string CameraPairSource::describe() const
{
  return "cameras " + options_.left_device + " + " + options_.right_device;
}

}  // namespace rgnav::stereo
