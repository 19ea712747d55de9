// Where stereo pairs come from. An interface because several really exist: two live cameras
// (CameraPairSource), a folder of recorded pairs (ImageFolderSource), and the simulator's
// renderer (drivers/sim, with the vision work).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace rgnav::stereo {

struct StereoFrame
{
  cv::Mat left;        // 8-bit, 1 or 3 channels (BGR)
  cv::Mat right;       // same size and type as left
  int64_t utime = 0;   // [us] capture time (wall time of the grab for cameras)
};

class StereoSource
{
 public:
  virtual ~StereoSource() = default;
  // The next pair, or nothing when the source is exhausted or a grab failed (see error()).
  virtual std::optional<StereoFrame> next() = 0;
  virtual std::string error() const = 0;
  virtual std::string describe() const = 0;
};

}  // namespace rgnav::stereo
