#include "drivers/stereo/image_folder_source.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "config/config.h"
#include "config/file_checks.h"
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
  // Refuse at start-up, naming the file, a folder whose first pair is no pair of images;
  // later damaged files are reported frame by frame (error()).
  std::string why;
  if (!read_pair(pairs_.front(), &why)) throw std::runtime_error("stereo folder '" + options_.folder + "': " + why);
}

std::optional<StereoFrame> ImageFolderSource::read_pair(const std::pair<std::string, std::string>& files,
                                                        std::string* why) const
{
  const int flags = options_.grayscale ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR;
  const auto read = [&](const std::string& file) {
    const std::string bytes = config::read_image_file(file, "image");   // whole, not cut off
    cv::Mat m = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data())), flags);
    if (m.empty()) throw config::ConfigError(file + ": cannot decode image");
    return m;
  };
  StereoFrame f;
  try {
    f.left = read(files.first);
    f.right = read(files.second);
  } catch (const config::ConfigError& e) {
    *why = e.what();
    return std::nullopt;
  }
  if (f.left.size() != f.right.size()) {
    *why = "left and right differ in size: " + files.first;
    return std::nullopt;
  }
  return f;
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
  auto f = read_pair(pairs_[index_++], &error_);
  if (!f) return std::nullopt;
  // Replayed files have no capture time of their own: stamp them when served.
  f->utime = time::wall_utime();
  ++served_;
  return f;
}

std::string ImageFolderSource::describe() const
{
  return "image folder " + options_.folder + " (" + std::to_string(pairs_.size()) + " pairs)";
}

}  // namespace rgnav::stereo
