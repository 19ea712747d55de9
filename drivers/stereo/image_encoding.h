// cv::Mat <-> image_t (raw GRAY8/BGR8 or JPEG).
#pragma once

#include <opencv2/core.hpp>

#include <optional>

#include "rgnav/image_t.hpp"

namespace rgnav::stereo {

enum class Encoding { kRaw, kJpeg };

// mat: CV_8UC1 or CV_8UC3 (BGR). jpeg_quality in [1, 100].
image_t encode_image(const cv::Mat& mat, int64_t utime, Encoding encoding, int jpeg_quality);
// Nothing if the data does not decode to an image of the declared size.
std::optional<cv::Mat> decode_image(const image_t& image);

}  // namespace rgnav::stereo
