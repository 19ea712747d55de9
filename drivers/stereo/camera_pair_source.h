// Two live cameras through OpenCV's V4L2 backend. Both are grabbed first and decoded after,
// so the two exposures are as close in time as the drivers allow.
#pragma once

#include <opencv2/videoio.hpp>

#include <string>

#include "drivers/stereo/stereo_source.h"

namespace rgnav::stereo {

struct CameraPairOptions
{
  std::string left_device = "/dev/video0";
  std::string right_device = "/dev/video1";
  int width = 640;
  int height = 480;
  double fps = 10;
  bool grayscale = false;
};

class CameraPairSource final : public StereoSource
{
 public:
  // Throws std::runtime_error naming the device that cannot be opened.
  explicit CameraPairSource(CameraPairOptions options);
  std::optional<StereoFrame> next() override;
  std::string error() const override { return error_; }
  std::string describe() const override;

 private:
  const CameraPairOptions options_;
  cv::VideoCapture left_;
  cv::VideoCapture right_;
  std::string error_;
};

}  // namespace rgnav::stereo
