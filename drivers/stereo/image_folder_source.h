// Stereo pairs from a folder of image files: every file whose name contains `left_token` is
// paired with the file named by replacing the last occurrence of that token with
// `right_token` (chessboard/left01.jpg + right01.jpg; aloe/aloeL.jpg + aloeR.jpg with tokens
// "L." and "R."). Pairs are served in file-name order, optionally looping.
#pragma once

#include <string>
#include <vector>

#include "drivers/stereo/stereo_source.h"

namespace rgnav::stereo {

struct ImageFolderOptions
{
  std::string folder;
  std::string left_token = "left";
  std::string right_token = "right";
  bool loop = true;
  bool grayscale = false;
};

class ImageFolderSource final : public StereoSource
{
 public:
  // Throws std::runtime_error if the folder is missing or holds no complete pair, or if its
  // first pair cannot be read (an image empty, cut off, not decodable, or the two of different
  // sizes: the message names the file).
  explicit ImageFolderSource(ImageFolderOptions options);
  std::optional<StereoFrame> next() override;
  std::string error() const override { return error_; }
  std::string describe() const override;
  size_t pairs() const { return pairs_.size(); }

 private:
  const ImageFolderOptions options_;
  // Both images of a pair, whole and decoded; nullopt with `why` naming the file otherwise.
  std::optional<StereoFrame> read_pair(const std::pair<std::string, std::string>& files, std::string* why) const;

  std::vector<std::pair<std::string, std::string>> pairs_;
  size_t index_ = 0;
  int64_t served_ = 0;
  std::string error_;
};

}  // namespace rgnav::stereo
