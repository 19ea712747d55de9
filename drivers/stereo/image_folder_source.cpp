#include "drivers/stereo/image_folder_source.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "time/message_time.h"

namespace rgnav::stereo {

namespace fs = std::filesystem;

ImageFolderSource::ImageFolderSource(ImageFolderOptions options) : options_(std::move(options))
{
  if (!fs::is_directory(options_.folder)) throw std::runtime_error("stereo folder '" + options_.folder + "' does not exist");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(options_.folder))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const auto& n : names) {
    const auto at = n.rfind(options_.left_token);
    if (at == std::string::npos) continue;
    std::string right = n;
    right.replace(at, options_.left_token.size(), options_.right_token);
    if (std::binary_search(names.begin(), names.end(), right))
      pairs_.emplace_back(options_.folder + "/" + n, options_.folder + "/" + right);
  }
  if (pairs_.empty())
    throw std::runtime_error("stereo folder '" + options_.folder + "' holds no pair named by '" + options_.left_token +
                             "' / '" + options_.right_token + "'");
}

std::optional<StereoFrame> ImageFolderSource::next()
{
  if (index_ >= pairs_.size()) {
    if (!options_.loop) {
      error_ = "end of image sequence";
      return std::nullopt;
    }
    index_ = 0;
  }
  const auto& [l, r] = pairs_[index_++];
  const int flags = options_.grayscale ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR;
  StereoFrame f;
  f.left = cv::imread(l, flags);
  f.right = cv::imread(r, flags);
  if (f.left.empty() || f.right.empty()) {
    error_ = "cannot decode " + (f.left.empty() ? l : r);
    return std::nullopt;
  }
  if (f.left.size() != f.right.size()) {
    error_ = "left and right differ in size: " + l;
    return std::nullopt;
  }
  // Replayed files have no capture time of their own: stamp them when served.
  f.utime = time::wall_utime();
  ++served_;
  return f;
}

std::string ImageFolderSource::describe() const
{
  return "image folder " + options_.folder + " (" + std::to_string(pairs_.size()) + " pairs)";
}

}  // namespace rgnav::stereo
