#include "drivers/stereo/image_encoding.h"

#include <opencv2/imgcodecs.hpp>

#include <stdexcept>

namespace rgnav::stereo {

image_t encode_image(const cv::Mat& mat, int64_t utime, Encoding encoding, int jpeg_quality)
{
  if (mat.depth() != CV_8U || (mat.channels() != 1 && mat.channels() != 3))
    throw std::invalid_argument("encode_image: need an 8-bit grey or BGR image");
  image_t m;
  m.utime = utime;
  m.width = mat.cols;
  m.height = mat.rows;
  if (encoding == Encoding::kJpeg) {
    std::vector<uint8_t> buf;
    cv::imencode(".jpg", mat, buf, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
    m.pixel_format = image_t::FORMAT_JPEG;
    m.row_stride = 0;
    m.data = std::move(buf);
  } else {
    const cv::Mat c = mat.isContinuous() ? mat : mat.clone();
    m.pixel_format = c.channels() == 1 ? image_t::FORMAT_GRAY8 : image_t::FORMAT_BGR8;
    m.row_stride = static_cast<int32_t>(c.cols * c.channels());
    m.data.assign(c.datastart, c.dataend);
  }
  m.size = static_cast<int32_t>(m.data.size());
  return m;
}

std::optional<cv::Mat> decode_image(const image_t& m)
{
  cv::Mat out;
  if (m.pixel_format == image_t::FORMAT_JPEG) {
    out = cv::imdecode(m.data, cv::IMREAD_UNCHANGED);
  } else {
    const int type = m.pixel_format == image_t::FORMAT_GRAY8 ? CV_8UC1 : CV_8UC3;
    const int64_t need = static_cast<int64_t>(m.row_stride) * m.height;
    if (m.width <= 0 || m.height <= 0 || static_cast<int64_t>(m.data.size()) < need) return std::nullopt;
    out = cv::Mat(m.height, m.width, type, const_cast<uint8_t*>(m.data.data()), static_cast<size_t>(m.row_stride)).clone();
  }
  if (out.empty() || out.cols != m.width || out.rows != m.height) return std::nullopt;
  return out;
}

}  // namespace rgnav::stereo
